// The page's one Trusted Types policy. The CSP's
// `require-trusted-types-for 'script'` makes every script URL a typed value:
// the page loads scripts only from its own origin (its workers and the
// vendored chart libraries), so the policy passes same-origin URLs and
// refuses any other. It makes no HTML: the page writes text, never markup.

const policy = globalThis.trustedTypes?.createPolicy('torus', {
  createScriptURL(url) {
    const u = new URL(url, globalThis.location.href);
    if (u.origin !== globalThis.location.origin) throw new TypeError(`refused a script from another origin: ${u.href}`);
    return u.href;
  },
});

/** A script URL the CSP accepts (a plain string where Trusted Types are absent). */
export function scriptURL(url) {
  return policy ? policy.createScriptURL(String(url)) : String(url);
}
