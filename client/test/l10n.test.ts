// The translations: every UI string the client passes to vscode.l10n.t has one in each
// l10n bundle, and every %key% of package.json one in each package.nls file.
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { describe, it } from 'node:test';

const root = process.cwd();
const LOCALES = ['zh-cn', 'ja'];

function json(path: string): Record<string, unknown> {
  return JSON.parse(readFileSync(join(root, path), 'utf8')) as Record<string, unknown>;
}

/** The literal first arguments of l10n.t(...) and of the status module's t(...) in client/src. */
function uiStrings(): Set<string> {
  const found = new Set<string>();
  const dir = join(root, 'client', 'src');
  for (const name of readdirSync(dir).filter((n) => n.endsWith('.ts'))) {
    const source = readFileSync(join(dir, name), 'utf8');
    for (const m of source.matchAll(/(?<![A-Za-z.])(?:vscode\.l10n\.t|l10n\.t|t)\(\s*'((?:[^'\\]|\\.)*)'/g)) {
      found.add((m[1] ?? '').replace(/\\'/g, "'"));
    }
  }
  return found;
}

const placeholders = (text: string) => [...text.matchAll(/\{\d+\}/g)].map((m) => m[0]).sort();

describe('translations', () => {
  it('has every client UI string in each l10n bundle, with its placeholders', () => {
    const strings = uiStrings();
    assert.ok(strings.size >= 30, `only ${strings.size} UI strings found`);
    assert.equal(json('package.json')['l10n'], './l10n');
    for (const locale of LOCALES) {
      const bundle = json(`l10n/bundle.l10n.${locale}.json`);
      assert.deepEqual([...strings].filter((s) => !(s in bundle)), [], `missing in ${locale}`);
      assert.deepEqual(Object.keys(bundle).filter((s) => !strings.has(s)), [], `unused in ${locale}`);
      for (const [source, translated] of Object.entries(bundle)) {
        assert.equal(typeof translated, 'string');
        assert.deepEqual(placeholders(translated as string), placeholders(source), `${locale}: ${source}`);
      }
    }
  });

  it('has every %key% of package.json in package.nls.json and each translation', () => {
    const keys = new Set([...readFileSync(join(root, 'package.json'), 'utf8').matchAll(/"%([^%"]+)%"/g)].map((m) => m[1]));
    assert.ok(keys.size >= 30);
    const english = json('package.nls.json');
    assert.deepEqual(Object.keys(english).sort(), [...keys].sort());
    for (const locale of LOCALES) {
      const nls = json(`package.nls.${locale}.json`);
      assert.deepEqual(Object.keys(nls).sort(), [...keys].sort(), locale);
      for (const [key, text] of Object.entries(nls)) {
        // The walkthrough's command links must survive translation.
        const links = (s: unknown) => [...String(s).matchAll(/\(command:[^)]+\)/g)].map((m) => m[0]);
        assert.deepEqual(links(text), links(english[key]), `${locale}: ${key}`);
      }
    }
  });

  it('contributes the settings under the extension title, and no colour swatches', () => {
    const manifest = json('package.json') as {
      displayName: string;
      contributes: { configuration: Array<{ title: string }>; configurationDefaults: Record<string, unknown> };
    };
    const english = json('package.nls.json');
    const title = (t: string) => (t.startsWith('%') ? english[t.slice(1, -1)] : t);
    // A category titled as the extension is shown under the extension's own heading.
    assert.equal(title(manifest.contributes.configuration[0]?.title ?? ''), title(manifest.displayName));
    assert.equal(title(manifest.displayName), 'FANUC Macro B');
    assert.deepEqual(manifest.contributes.configurationDefaults['[fanuc-macro]'], { 'editor.colorDecorators': false });
  });

  it('ships the files the manifest names', () => {
    const ignore = readFileSync(join(root, '.vscodeignore'), 'utf8');
    for (const shipped of ['!package.nls.json', '!package.nls.*.json', '!l10n/bundle.l10n.*.json', '!docs/rules.md', '!media/walkthrough/*.md', '!samples/*.nc']) {
      assert.ok(ignore.split('\n').includes(shipped), shipped);
    }
    const manifest = readFileSync(join(root, 'package.json'), 'utf8');
    // A walkthrough step's page is named by a %key%: each language's file of its own.
    for (const nls of ['package.nls.json', ...LOCALES.map((l) => `package.nls.${l}.json`)]) {
      const said = json(nls);
      for (const m of manifest.matchAll(/"markdown": "([^"]+)"/g)) {
        const named = m[1] ?? '';
        const path = named.startsWith('%') ? String(said[named.slice(1, -1)]) : named;
        assert.ok(readFileSync(join(root, path), 'utf8').length > 0, `${nls}: ${path}`);
      }
    }
  });

  it('has the pages of the walkthrough in Chinese', () => {
    const english = json('package.nls.json');
    const chinese = json('package.nls.zh-cn.json');
    const media = Object.keys(english).filter((k) => k.startsWith('walkthrough.') && k.endsWith('.media'));
    assert.equal(media.length, 5);
    for (const key of media) {
      // VS Code's own name for a page's translation (<page>.nls.<locale>.md), named by the key too.
      assert.equal(chinese[key], String(english[key]).replace(/\.md$/, '.nls.zh-cn.md'), key);
      const page = readFileSync(join(root, String(chinese[key])), 'utf8');
      assert.match(page, /^# \S*[\u4e00-\u9fff]/u, key);
    }
  });
});
