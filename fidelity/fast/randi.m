function ri = randi (imax)
  % randi(2), the only call MCTSgaussian.m makes (in randmovetor.m), as
  % Octave 7.3's randi.m computes it, without its argument checks: about
  % half of the script's time under Octave. One rand per value, mapped as
  % randi.m maps it: r = floor(rand * 2^53) (flintmax()+1 rounds to 2^53),
  % K = floor(2^53 / 2) = 2^52, no draw rejected, ri = 1 + floor(r / K).
  % run_code.sh uses it only when FAST_RANDI=1; any other call is refused.
  if (nargin != 1 || ! isequal (imax, 2))
    error ('fidelity randi: only randi(2) is provided');
  end
  ri = 1 + floor (floor (rand () * 9007199254740992) / 4503599627370496);
end
