// The designer under a user's hands (issue 28), checked in the page
// tests/js/designer_test.mjs opened (1366 x 768): the title names the preset and
// its file; the buttons never move while the status, the causes and the repair's
// result come and go; Repair keeps t* (unless it says it moved it) and the
// camera; a click on a cause selects the handle of the field to change and
// highlights the panel; the handle under the pointer lights up with its name;
// one number format on the panel. Screenshots of each state beside `screenshot`.
import { readFileSync } from 'node:fs';

/// `page`: the designer on presets/default.json; `preset`: its file; `check(ok, what)`
/// records a failure; `settled()` waits for the buildability report.
export async function checkUnderHands({ page, preset, check, settled, screenshot }) {
  const api = (f, ...args) => page.evaluate(f, ...args);
  const shot = async (suffix) => { if (screenshot) await page.screenshot({ path: screenshot.replace(/\.png$/, `-${suffix}.png`) }); };
  const still = () => page.waitForFunction(() => !window.phedraDesigner.cameraMoving(), null, { timeout: 10000 });
  const original = JSON.parse(readFileSync(preset, 'utf8'));

  // The title: the preset's name and, when it says more, the file it came from.
  {
    const [title, file, tab] = await Promise.all([page.$eval('#title', (e) => e.textContent), page.$eval('#file', (e) => e.textContent), page.title()]);
    check(title === original.name && file === 'default.json' && tab.includes(original.name) && tab.includes('default.json'),
      `title "${title}", file "${file}", tab "${tab}" for ${original.name} from default.json`);
  }

  // The buttons and the other controls stay where they are over the status changes below.
  // `id@x,y` of every control outside the status box, in one task of the page (a
  // repair finishing in between would rebuild the sign buttons under the snapshot).
  await page.evaluate(() => {
    window.controlsAt = () => [...document.querySelectorAll('#panel button, #panel select, #panel input, #panel label')]
      .filter((e) => e.offsetParent !== null && !e.closest('#status-box'))
      .map((e) => { const r = e.getBoundingClientRect(); return `${e.id || e.textContent.trim().slice(0, 12)}@${Math.round(r.left)},${Math.round(r.top)}`; });
  });
  const controls = () => page.evaluate(() => window.controlsAt());
  const layouts = [];
  const layout = async (what) => layouts.push({ what, at: await controls() });

  check(await api((p) => window.phedraDesigner.apply(p), original), 'the default preset again');
  await settled();
  await layout('a buildable design');

  // A design with bow-ties whose nearest buildable design, searched freely, moves t*
  // (apex S_2 raised above S_1: the free search lowers S_1, which t measures).
  const broken = JSON.parse(JSON.stringify(original));
  broken.apex_heights[2] = 1.2;
  check(await api((p) => window.phedraDesigner.apply(p), broken), 'the design with S_2 above S_1 refused');
  const b = await settled();
  check(!b.buildable && b.invalid.length > 0, `S_2 above S_1: ${b.summary}`);
  await layout('not buildable, with its causes');
  await shot('before-repair');

  // Causes for a maker first: each starts with what to change; a click selects its handle and highlights its panel.
  {
    const first = await page.$eval('#why-list li', (e) => e.textContent);
    check(first.startsWith('change: ') && first.includes('details'), `the first cause reads "${first.slice(0, 120)}"`);
    const cause = b.invalid[0];
    const field = cause.hints.map((h) => /\b[a-z_][a-z_\d]*(?:\[\d+\]|\.[a-z_]+)*/g.exec(h.replace(/^\w+ /, ''))?.[0]).find(Boolean);
    await page.click('#why-list li .change');  // its first change
    await page.waitForTimeout(100);
    const selected = await api(() => window.phedraDesigner.selectedHandle());
    const key = field.replace(/\[\d+\]$/, '').replace(/\[(\d+)\]/g, '.$1'), index = Number(/\[(\d+)\]$/.exec(field)?.[1] ?? -1);
    const wanted = key.startsWith('trajectory') ? { key: 'trajectory', index: Number(/^trajectory\[(\d+)\]/.exec(field)[1]) } : { key, index };
    check(selected && selected.key === wanted.key && selected.index === wanted.index,
      `a click on the cause of panel ${cause.panel} ("${cause.hints[0]}") selected ${JSON.stringify(selected)}, not ${JSON.stringify(wanted)}`);
    check(await api(() => window.phedraDesigner.highlightedPanel()) === cause.panel, `panel ${cause.panel} not highlighted`);
    const label = await api(() => window.phedraDesigner.handleLabel());
    const shownField = wanted.key.replace(/\.(\d+)/g, '[$1]') + (wanted.index >= 0 ? `[${wanted.index}]` : '');
    check(label.includes(` · ${shownField}`), `the selected handle's label "${label}" does not name ${shownField}`);
    check(!(await page.$eval('#panel-label', (e) => e.hidden)) && (await page.$eval('#panel-label', (e) => e.textContent)) === `panel ${cause.panel}`,
      'no "panel N" label on the highlighted panel');
    await layout('a cause selected');
    await shot('cause');
  }

  // The handle nearest the pointer lights up, with its name.
  {
    const at = await api(() => window.phedraDesigner.handleScreen('apex_heights', 4));
    await page.mouse.move(at[0] + 4, at[1] + 3);
    await page.waitForTimeout(100);
    const hovered = await api(() => window.phedraDesigner.hoveredHandle());
    const label = await api(() => window.phedraDesigner.handleLabel());
    check(hovered?.key === 'apex_heights' && hovered.index === 4 && label.startsWith('apex S_4 · apex_heights[4]'),
      `hovering apex S_4: ${JSON.stringify(hovered)}, label "${label}"`);
    await shot('hover');
    await page.mouse.move(5, 760);
  }

  // Repair keeps t* and the camera; the buttons stay put while it searches and after.
  {
    const before = { t: (await api(() => window.phedraDesigner.info())).t_star, d: await api(() => window.phedraDesigner.cameraDistance()) };
    // The controls while the search runs (it holds the thread: seen from the page, as the status says so).
    await page.evaluate(() => {
      window.whileRepairing = null;
      const watch = new MutationObserver(() => {
        if (/^repairing/.test(document.getElementById('repair-result').textContent)) {
          window.whileRepairing = window.controlsAt();
          watch.disconnect();
        }
      });
      watch.observe(document.getElementById('repair-result'), { childList: true, characterData: true, subtree: true });
    });
    await page.click('#repair');
    await page.waitForFunction(() => /^(repaired|not repaired|repair refused)/.test(document.getElementById('repair-result').textContent),
      null, { timeout: 60000 });
    const result = await page.$eval('#repair-result', (e) => e.textContent);
    check(result.startsWith('repaired: '), `repair result: "${result}"`);
    const repairing = await page.evaluate(() => window.whileRepairing);
    check(repairing !== null, 'no "repairing" status while the search ran');
    if (repairing) layouts.push({ what: 'repairing', at: repairing });
    const after = await settled();
    await page.waitForTimeout(200);
    await still();
    const now = { t: (await api(() => window.phedraDesigner.info())).t_star, d: await api(() => window.phedraDesigner.cameraDistance()) };
    const moved = await api(() => window.phedraDesigner.lastRepair());
    check(after.buildable, `after the repair: ${after.summary}`);
    check(now.t === before.t || (moved?.moved && result.includes('t* moved from')),
      `t* ${before.t} -> ${now.t} after the repair, which says "${result}"`);
    check(now.t === before.t && result.includes(`t* kept at ${before.t.toFixed(4)}`), `the repair did not keep t* = ${before.t}: "${result}"`);
    check(Math.abs(now.d - before.d) <= 0.1 * before.d, `the camera's distance ${before.d} -> ${now.d} after the repair`);
    const t = await api(() => window.phedraDesigner.t());
    check(Math.abs(t - before.t) < 1e-3, `the slider left t* = ${before.t} for ${t}`);
    await layout('repaired');
    await shot('after-repair');
    // Undo: the repair's message goes, another status comes.
    await page.click('#undo');
    await settled();
    await layout('repair undone');
  }

  // A refused edit: the message in red, next to its handle; nothing moves either.
  {
    const p = JSON.parse(JSON.stringify(original));
    p.directions[2] = [0, 0, 1];
    await api((q) => window.phedraDesigner.apply(q), p);
    await page.waitForTimeout(100);
    check((await api(() => window.phedraDesigner.message())).startsWith('directions[2]: '), 'the refusal is not shown');
    await layout('a refusal');
  }
  const first = layouts[0];
  for (const { what, at } of layouts.slice(1)) {
    const moved = at.filter((x) => !first.at.includes(x)), were = first.at.filter((x) => !at.includes(x));
    check(moved.length === 0 && were.length === 0, `the controls moved (${what}): ${moved.slice(0, 5).join(' ')}; they were ${were.slice(0, 5).join(' ')}`);
  }
  check(layouts.length >= 6, `${layouts.length} status changes looked at`);

  // One number format: the panel writes every decimal with 4 decimals (or in exponent form when tiny).
  {
    check(await api((p) => window.phedraDesigner.apply(p), broken), 'the broken design again');
    await settled();
    const text = await page.$eval('#panel', (e) => [...e.querySelectorAll('#status-box, #kind, .row:not(#scale)')].map((x) => x.textContent).join(' '));
    const odd = (text.match(/(?<![\w.[])-?\d+\.\d+(?:e[-+]?\d+)?(?![\d.]|\s*%)/g) ?? []).filter((x) => !/^-?\d+\.\d{4}$/.test(x) && !/e[-+]\d+$/.test(x));
    check(odd.length === 0, `numbers in another format on the panel: ${odd.slice(0, 6).join(', ')}`);
    check(!/flexion interval \[/.test(await page.$eval('#status-box', (e) => e.textContent)), 'the status repeats the flexion interval the ticks show');
  }
  check(await api((p) => window.phedraDesigner.apply(p), original), 'the default preset again');
  await settled();
  return layouts.length;
}
