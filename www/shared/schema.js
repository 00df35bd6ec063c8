// How the page reads the engine's schema: one function per kind of entry.
//
// Fields the page reads from a parameter entry (schema().params[i]):
//   key, kind, default, min, max, min_open, choices, allowed, help
//   label          short human label
//   group          "game", or the searcher that declares it
//   advanced       behind "More settings"
//   choice_labels  labels for people, in the order of `choices`, where the
//                  parameter gives them (the searcher's come from
//                  schema.searchers; other choices show their names)
// and from the schema itself: groups [{ name, label }].
//
// Pure module (no DOM), so Node tests can use it with the real engine's schema.


/**
 * One parameter entry as the page uses it. `choiceLabel(c)` is the label of
 * choice `c` for people: the engine's, else (for the searcher choices,
 * which the registry names) the registry's label, else `c` itself.
 */
export function paramEntry(p, schema) {
  const labels = new Map();
  if (Array.isArray(p.choice_labels)) p.choices?.forEach((c, i) => p.choice_labels[i] && labels.set(c, p.choice_labels[i]));
  else if (p.choice_labels && typeof p.choice_labels === 'object') for (const [c, l] of Object.entries(p.choice_labels)) labels.set(c, l);
  else if (p.choices && schema?.searchers?.length && p.choices.every((c) => schema.searchers.some((s) => s.name === c))) {
    for (const s of schema.searchers) labels.set(s.name, s.label);
  }
  return {
    ...p,
    label: p.label,
    group: p.group,
    advanced: p.advanced,
    choiceLabel: (c) => labels.get(c) ?? c,
  };
}

/** Every parameter entry of the schema, in the schema's order. */
export function paramEntries(schema) {
  return schema.params.map((p) => paramEntry(p, schema));
}

/** The entry of parameter `key` (undefined if the schema has none). */
export function paramByKey(schema, key) {
  const p = schema.params.find((q) => q.key === key);
  return p && paramEntry(p, schema);
}

/** A group's label for people. */
export function groupLabel(schema, name) {
  return schema.groups.find((g) => g.name === name)?.label ?? name;
}
