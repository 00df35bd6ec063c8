#!/usr/bin/env bash
# Assemble dist/: a self-contained static copy of the page (index.html,
# www/ with pkg/ and vendor/, docs/ images if present) that works from any
# static host, at any path, offline. Assumes scripts/build.sh ran.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

for f in index.html www/pkg/torus_search.js www/pkg/torus_search_bg.wasm; do
  [[ -f "$f" ]] || { echo "error: $f missing (run make build)" >&2; exit 1; }
done

rm -rf dist
mkdir -p dist
cp index.html dist/
# www/ as served, without TypeScript declarations and package metadata.
cp -R www dist/www
rm -f dist/www/pkg/*.d.ts dist/www/pkg/package.json dist/www/pkg/.gitignore
if [[ -d docs ]]; then
  while IFS= read -r -d '' img; do
    mkdir -p "dist/$(dirname "$img")"
    cp "$img" "dist/$img"
  done < <(find docs -type f \( -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.gif' -o -iname '*.svg' -o -iname '*.webp' \) -print0)
fi

# The page's CSP as a header too (hosts that read _headers: Netlify,
# Cloudflare Pages), so workers and the page run under it, plus nosniff.
# The meta tag in index.html is the one source; docs/deploy.md has the same
# two headers for other hosts.
csp="$(sed -n 's/.*http-equiv="Content-Security-Policy" content="\([^"]*\)".*/\1/p' index.html)"
[[ -n "$csp" ]] || { echo "error: index.html has no CSP meta tag" >&2; exit 1; }
printf '/*\n  Content-Security-Policy: %s\n  X-Content-Type-Options: nosniff\n' "$csp" > dist/_headers

# Relative URLs only: no src/href in the HTML may start with "/" or name a host.
if grep -RInE '(src|href)="(/|[a-z]+://)' dist --include='*.html'; then
  echo "error: dist/ HTML uses absolute URLs (above); use relative ones" >&2
  exit 1
fi
echo "[dist] dist/: $(find dist -type f | wc -l) files, $(du -sh dist | cut -f1)"
