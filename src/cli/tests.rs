//! The command line's own checks.

#[test]
fn the_command_is_well_formed() {
    super::command().debug_assert();
}
