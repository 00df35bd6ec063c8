// The part of a result file that must compare equal between runs (the page
// and the CLI; shards merged and one run): the text without its provenance,
// as src/experiment/provenance.rs's `strip` takes it out. A result JSON
// loses its top-level "provenance" member, a CSV its leading "#" lines.

/** `text` without its provenance. */
export function stripProvenance(text) {
  if (text.startsWith('#')) {
    const lines = text.split('\n');
    let i = 0;
    while (i < lines.length && lines[i].startsWith('#')) i++;
    return lines.slice(i).join('\n');
  }
  const key = ',"provenance":';
  const at = text.indexOf(key);
  if (at < 0) return text;
  let depth = 0;
  let inString = false;
  let escaped = false;
  for (let i = at + key.length; i < text.length; i++) {
    const c = text[i];
    if (escaped) escaped = false;
    else if (c === '\\' && inString) escaped = true;
    else if (c === '"') inString = !inString;
    else if (!inString && (c === '{' || c === '[')) depth++;
    else if (!inString && (c === '}' || c === ']')) {
      depth--;
      if (depth === 0) return text.slice(0, at) + text.slice(i + 1);
    }
  }
  return text;
}
