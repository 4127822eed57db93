import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, it } from 'node:test';
import { RULES_URL, headingAnchor, headingLine, ruleAnchorOf, ruleCommandUri, ruleLinkOf } from '../src/ruleDocs';

const root = process.cwd();
const rulesDoc = readFileSync(join(root, 'docs', 'rules.md'), 'utf8');

describe('rule documentation links', () => {
  it('point at the page the server links to', () => {
    // The server's RULES_URL (rules_doc.py, which the language server and the SARIF output
    // link through): the client recognises exactly that page.
    const rulesDocPy = readFileSync(join(root, 'server', 'fanuc_macro', 'rules_doc.py'), 'utf8');
    assert.match(rulesDocPy, new RegExp(`^RULES_URL = "${RULES_URL.replace(/[.]/g, '\\.')}"$`, 'm'));
    assert.equal(ruleAnchorOf(`${RULES_URL}#mb601-m-not-integer`), 'mb601-m-not-integer');
    assert.equal(ruleAnchorOf(RULES_URL), '');
    assert.equal(ruleAnchorOf('https://example.com/docs/rules.md#mb601'), undefined);
    assert.equal(ruleAnchorOf(`${RULES_URL}#"><script>`), undefined);
  });

  it('open the Chinese page where the server links to it, at the same section', () => {
    const chinese = RULES_URL.replace(/rules\.md$/, 'rules.zh-cn.md');
    assert.deepEqual(ruleLinkOf(`${chinese}#mb101-goto-missing-label`), {
      page: 'rules.zh-cn.md',
      anchor: 'mb101-goto-missing-label',
    });
    assert.equal(ruleLinkOf(RULES_URL.replace(/rules\.md$/, 'rules.de.md')), undefined);
    const uri = ruleCommandUri('mb101-goto-missing-label', 'rules.zh-cn.md');
    const query = uri.slice(uri.indexOf('?') + 1);
    assert.deepEqual(JSON.parse(decodeURIComponent(query)), ['mb101-goto-missing-label', 'rules.zh-cn.md']);
    // The Chinese page has every rule's heading, with the English page's anchors.
    const zh = readFileSync(join(root, 'docs', 'rules.zh-cn.md'), 'utf8');
    for (const [, text] of rulesDoc.matchAll(/^## ((MB\d{3}) (\S+))$/gm)) {
      assert.ok(headingLine(zh, headingAnchor(text ?? '')) >= 0, text);
    }
  });

  it('become a command URI with the anchor as its JSON argument', () => {
    const uri = ruleCommandUri('mb601-m-not-integer');
    assert.equal(uri, 'command:fanuc-macro.openRuleDocumentation?%5B%22mb601-m-not-integer%22%5D');
    const query = uri.slice(uri.indexOf('?') + 1);
    assert.deepEqual(JSON.parse(decodeURIComponent(query)), ['mb601-m-not-integer']);
  });

  it('find the heading of every rule in the shipped page', () => {
    const headings = [...rulesDoc.matchAll(/^## ((MB\d{3}) (\S+))$/gm)];
    assert.ok(headings.length >= 50, `only ${headings.length} rule headings`);
    const lines = rulesDoc.split('\n');
    for (const [, text, code] of headings) {
      const anchor = headingAnchor(text ?? '');
      const line = headingLine(rulesDoc, anchor);
      assert.equal(lines[line], `## ${text}`, anchor);
      // The code alone (a rule renamed since the server's link was made) finds it too.
      assert.equal(headingLine(rulesDoc, (code ?? '').toLowerCase()), line, code);
    }
    assert.equal(headingLine(rulesDoc, 'how-the-evaluator-runs-a-program') >= 0, true);
    assert.equal(headingLine(rulesDoc, 'no-such-section'), -1);
  });

  it('make anchors as GitHub does, outside code fences', () => {
    assert.equal(headingAnchor('MB601 m-not-integer'), 'mb601-m-not-integer');
    assert.equal(headingAnchor('Suppressing a diagnostic on one line'), 'suppressing-a-diagnostic-on-one-line');
    assert.equal(headingAnchor('`G65` calls & arguments'), 'g65-calls--arguments');
    const text = '# Top\n```\n## MB100 fake\n```\n## MB100 real\n';
    assert.equal(headingLine(text, 'mb100-real'), 4);
    assert.equal(headingLine(text, 'mb100-fake'), 4); // by its code: the fenced one is no heading
  });
});
