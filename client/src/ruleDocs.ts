// The rules' documentation shipped with the extension (docs/rules.md in the .vsix). The server
// links each diagnostic's code to that page's section on the project's web site
// (codeDescription.href, rules_doc.py); the client turns such a link into a command that opens
// the shipped page at the section, so the link works offline and for the version installed.
// Pure logic, no `vscode` import.

/** The page the server's codeDescription links point to (RULES_URL in rules_doc.py). */
export const RULES_URL = 'https://github.com/fanuc-macro/fanuc-macro/blob/main/docs/rules.md';

/** The page in the extension's folder. */
export const RULES_DOC_PATH = ['docs', 'rules.md'] as const;

/** The pages in other languages beside it (PAGES in rules_doc.py): the server links a Chinese
 * client's diagnostics to docs/rules.zh-cn.md, with the same anchors. */
export const RULES_PAGES = ['rules.md', 'rules.zh-cn.md'] as const;
export type RulesPage = (typeof RULES_PAGES)[number];

/** The page and section a link to one of the rules pages names, or undefined for another link. */
export function ruleLinkOf(href: string): { page: RulesPage; anchor: string } | undefined {
  const hash = href.indexOf('#');
  const url = hash < 0 ? href : href.slice(0, hash);
  const base = RULES_URL.slice(0, RULES_URL.length - 'rules.md'.length);
  const page = RULES_PAGES.find((name) => url === base + name);
  if (page === undefined) return undefined;
  const anchor = hash < 0 ? '' : decodeURIComponent(href.slice(hash + 1));
  return /^[a-z0-9-]*$/.test(anchor) ? { page, anchor } : undefined;
}

export const OPEN_RULE_COMMAND = 'fanuc-macro.openRuleDocumentation';

/** The section a link to the rules page names (`mb601-m-not-integer`), or undefined for another link. */
export function ruleAnchorOf(href: string): string | undefined {
  return ruleLinkOf(href)?.anchor;
}

/** The command URI that opens the shipped `page` at `anchor` (arguments as a JSON array; the
 * English page's link has the anchor alone). */
export function ruleCommandUri(anchor: string, page: RulesPage = 'rules.md'): string {
  const args = page === 'rules.md' ? [anchor] : [anchor, page];
  return `command:${OPEN_RULE_COMMAND}?${encodeURIComponent(JSON.stringify(args))}`;
}

/** A heading's anchor as GitHub makes it: lower case, punctuation dropped, spaces to hyphens. */
export function headingAnchor(heading: string): string {
  return heading
    .trim()
    .toLowerCase()
    .replace(/[^\p{L}\p{N}\s_-]/gu, '')
    .replace(/\s/g, '-');
}

/**
 * The 0-based line of the heading whose anchor is `anchor` (outside fenced code), or of the
 * rule's heading when only the code matches (`mb601` finds `## MB601 ...`); -1 when none.
 */
export function headingLine(markdown: string, anchor: string): number {
  const lines = markdown.split(/\r?\n/);
  let fenced = false;
  let byCode = -1;
  const code = /^[a-z]{2}\d{3}/.exec(anchor)?.[0];
  for (let i = 0; i < lines.length; i++) {
    const line = lines[i] ?? '';
    if (/^\s*(```|~~~)/.test(line)) fenced = !fenced;
    if (fenced) continue;
    const heading = /^#{1,6}\s+(.*?)\s*#*\s*$/.exec(line);
    if (heading === null) continue;
    const text = heading[1] ?? '';
    if (headingAnchor(text) === anchor) return i;
    if (byCode < 0 && code !== undefined && text.toLowerCase().startsWith(`${code} `)) byCode = i;
  }
  return byCode;
}
