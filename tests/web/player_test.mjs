// The browser player in a real browser: pages written by `raystep export-html` from a grid, a kd-tree and an
// 8-wide BVH trace of the Cornell box and from a 2D scene's ray, opened from disk (no network) in Debian's
// Chromium driven by Playwright. At each step visited with the keys the page's state and Why text must
// equal `raystep replay --step N` on the same trace; the 2D page draws the walk's current node, the 3D pages
// (three.js) the current box, the stack's and the ray, checked in the canvas's pixels. A lesson's
// page: its questions answered by clicking, against `raystep lesson answers`. The site of every lesson: each
// page opens and steps to its end. Screenshots are kept beside the other artefacts to look at.
//   node tests/web/player_test.mjs RAYSTEP_EXE SOURCE_DIR OUT_DIR
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const [exe, source, out] = process.argv.slice(2);
const require = createRequire(path.join(source, 'web', 'package.json'));
const { chromium } = require('playwright-core');
fs.mkdirSync(out, { recursive: true });

const raystep = (...args) => execFileSync(exe, args, { cwd: source, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

// The state after event `step` as `raystep replay` writes it: split into the state and the Why text, as the
// page shows them.
function replayed(trace, step) {
  const text = raystep('replay', trace, '--step', String(step));
  const block = text.slice(text.indexOf('\n\n') + 2).replace(/\n+$/, '\n');
  const at = block.indexOf('\n  why: ');
  if (at < 0) return { state: block, why: '' };
  return { state: block.slice(0, at + 1), why: block.slice(at + 8).replace(/\n {7}/g, '\n').replace(/\n$/, '') };
}

const cases = [
  { name: 'grid', trace: ['scenes/cornell.json', '--accel', 'grid', '--pixel', '160,200'] },
  { name: 'kd', trace: ['scenes/cornell.json', '--accel', 'kd', '--pixel', '160,200'] },
  { name: 'bvh8', trace: ['scenes/cornell.json', '--accel', 'bvh8', '--pixel', '160,200'] },
  { name: 'flat-kd', trace: ['scenes/flatland/kd_traversal.json', '--accel', 'kd'], flat: true },
];

const browser = await chromium.launch({
  executablePath: process.env.RAYSTEP_CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
         '--disable-component-update', '--disable-sync'],
});
let failures = 0;
try {
  for (const c of cases) {
    const trace = path.join(out, `player-${c.name}.trace.json`);
    const page_file = path.join(out, `player-${c.name}.html`);
    raystep('trace', ...c.trace, '-o', trace);
    // A trace's page, or for the 2D scene the page of its own ray through the structure (the same walk).
    if (c.flat) raystep('export-html', c.trace[0], '--accel', c.trace[2], '-o', page_file);
    else raystep('export-html', trace, '-o', page_file);
    const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
    const requests = [];
    page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) requests.push(r.url()); });
    try {
      await page.goto('file://' + page_file);
      await page.waitForSelector('body[data-ready="true"]', { timeout: 10000 });
      const events = await page.evaluate(() => window.raystep.data.walks[0].rays[0].lines.length);
      assert.ok(events > 3, `${c.name}: ${events} events`);
      // Step with the keys as in the debugger: Right a few times, Left once, End, Home.
      const visit = [];
      for (let k = 0; k < Math.min(6, events - 1); ++k) {
        await page.keyboard.press('ArrowRight');
        visit.push(k + 1);
      }
      await page.keyboard.press('ArrowLeft');
      visit.push(visit[visit.length - 1] - 1);
      let k = visit[visit.length - 1];
      assert.equal(await page.evaluate(() => window.raystep.step), k, `${c.name}: the keys step`);
      for (const [key, want] of [['End', events - 1], ['Home', 0]]) {
        await page.keyboard.press(key);
        assert.equal(await page.evaluate(() => window.raystep.step), want, `${c.name}: ${key}`);
      }
      for (const step of [1, Math.floor(events / 2), events - 1]) {
        await page.evaluate((s) => window.raystep.go(s), step);
        const shown = { state: await page.textContent('#state'), why: await page.textContent('#why') };
        const want = replayed(trace, step);
        assert.equal(shown.state, want.state, `${c.name} step ${step}: the state`);
        assert.equal(shown.why, want.why, `${c.name} step ${step}: the Why text`);
        const current = await page.textContent('#events li.current');
        assert.ok(want.state.startsWith(`${step}  ${current.trim().split(/\s+/)[0]}`), `${c.name} step ${step}: the event list`);
      }
      if (!c.flat) {
        // The 3D view (three.js): at each step the box the data names current, the stack's, drawn; the current
        // box's yellow in the canvas at a node or cell, none at the ray's start and end; the ray in red.
        assert.equal(await page.locator('#view3d canvas').count(), 1, 'the 3D view');
        const walk = await page.evaluate(() => window.raystep.data.walks[0].rays[0].walk3d);
        assert.ok(walk.boxes.length > 0, 'the walk carries boxes');
        const pixels = () => page.evaluate(() => {
          const src = window.raystep.view3d.canvas;
          const copy = document.createElement('canvas');
          copy.width = src.width;
          copy.height = src.height;
          const g = copy.getContext('2d');
          g.drawImage(src, 0, 0);
          const d = g.getImageData(0, 0, copy.width, copy.height).data;
          let yellow = 0, red = 0;
          for (let i = 0; i < d.length; i += 4) {
            if (d[i] - d[i + 2] > 40 && d[i + 1] - d[i + 2] > 25) ++yellow;
            if (d[i] > 150 && d[i + 1] < 90 && d[i + 2] < 90) ++red;
          }
          return { yellow, red };
        });
        const inner = walk.current.findIndex((b) => b >= 0);
        assert.ok(inner > 0, 'a step with a current box');
        for (const k of [0, inner, events - 1]) {
          await page.evaluate((s) => window.raystep.go(s), k);
          const shown = await page.evaluate(() => ({ ...window.raystep.view3d.shown }));
          assert.equal(shown.current, walk.current[k], `${c.name} step ${k}: the current box`);
          assert.equal(shown.stack, walk.stack[k].length, `${c.name} step ${k}: the stack's boxes`);
          const px = await pixels();
          assert.ok(px.red > 100, `${c.name} step ${k}: the ray is drawn (${px.red} red pixels)`);
          if (walk.current[k] >= 0) assert.ok(px.yellow > 500, `${c.name} step ${k}: the current box (${px.yellow})`);
          else assert.ok(px.yellow < 50, `${c.name} step ${k}: no current box (${px.yellow})`);
        }
        await page.evaluate((s) => window.raystep.go(s), inner);
      }
      if (c.flat) {
        // The slides' picture: at step 7 the current leaf LLL in yellow with LLR and R stacked, captioned so.
        await page.evaluate(() => window.raystep.go(7));
        assert.equal(await page.locator('#pic-walk polygon.current').count(), 1, 'the current leaf is drawn');
        assert.equal(await page.locator('#pic-walk polygon.stacked').count(), 2, 'the stacked nodes are drawn');
        assert.match(await page.textContent('#caption'), /Stack: LLR,R {3}Current: LLL/);
        assert.ok(await page.locator('#pic-under line.split').count() > 3, 'the split lines are drawn');
      }
      await page.screenshot({ path: path.join(out, `player-${c.name}.png`) });
      assert.deepEqual(requests, [], `${c.name}: the page asks the network for nothing`);
      const error = await page.evaluate(() => document.body.dataset.error || '');
      assert.equal(error, '', `${c.name}: the page's script`);
      console.log(`ok ${c.name}: ${events} events, ${(fs.statSync(page_file).size / 1024).toFixed(1)} KiB`);
    } catch (e) {
      ++failures;
      console.error(`FAILED ${c.name}: ${e.message}`);
    } finally {
      await page.close();
    }
  }

  // A lesson's page: the question at its step hides what gives the answer away; a wrong choice says why
  // not (core's feedback), the right one shows the answer, as `raystep lesson answers` gives it.
  const lessonPage = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  try {
    const lesson = path.join(source, 'lessons', '09-3d-dda.md');
    const file = path.join(out, 'player-lesson-09.html');
    raystep('export-html', lesson, '-o', file);
    await lessonPage.goto('file://' + file);
    await lessonPage.waitForSelector('body[data-ready="true"]', { timeout: 10000 });
    const answers = raystep('lesson', 'answers', lesson).split('\n');
    const steps = await lessonPage.evaluate(() => window.raystep.data.lesson.steps);
    let asked = 0;
    for (const [i, st] of steps.entries()) {
      if (!st.question) continue;
      ++asked;
      await lessonPage.evaluate((k) => window.raystep.lessonStep(k), i);
      assert.equal(await lessonPage.textContent('#lesson-title'), st.title);
      assert.equal(await lessonPage.isVisible('#answer'), false, `step ${i + 1}: the answer waits`);
      assert.equal(await lessonPage.textContent('#why'), 'Shown with the answer.');
      assert.equal(await lessonPage.locator('#events li.later').count(),
                   await lessonPage.evaluate(() => window.raystep.data.walks[0].rays[0].lines.length) - 1 - st.step);
      const at = answers.findIndex((l) => l.startsWith(`step ${i + 1} '`));
      assert.ok(at >= 0, `step ${i + 1} in raystep lesson answers`);
      const choices = lessonPage.locator('#choices button');
      const wrong = st.question.choices.findIndex((c) => !c.right);
      const right = st.question.choices.findIndex((c) => c.right);
      assert.ok(right >= 0 && wrong >= 0, `step ${i + 1}: a right and a wrong choice`);
      await choices.nth(wrong).click();
      assert.match(await lessonPage.textContent('#verdict'), /^Not quite\./);
      assert.equal(await lessonPage.isVisible('#answer'), false);
      await choices.nth(right).click();
      assert.equal(await lessonPage.textContent('#verdict'), 'Right.');
      assert.equal(await lessonPage.isVisible('#answer'), true);
      assert.ok(answers[at].endsWith(': ' + await lessonPage.textContent('#answer-text')), answers[at]);
      assert.equal('  ' + await lessonPage.textContent('#answer-why'), answers[at + 1]);
      assert.equal(await lessonPage.locator('#events li.later').count(), 0, 'the events after it show');
      assert.notEqual(await lessonPage.textContent('#why'), 'Shown with the answer.');
      if (asked === 1) await lessonPage.screenshot({ path: path.join(out, 'player-lesson-09.png'), fullPage: true });
    }
    assert.ok(asked >= 2, `${asked} questions`);
    console.log(`ok lesson 09: ${steps.length} steps, ${asked} questions`);
  } catch (e) {
    ++failures;
    console.error(`FAILED lesson page: ${e.message}`);
  } finally {
    await lessonPage.close();
  }

  // The site of every lesson: the index links each, and each page opens offline and steps to its end.
  try {
    const site = path.join(out, 'site');
    raystep('export-html', path.join(source, 'lessons'), '-o', site);
    const lessons = fs.readdirSync(path.join(source, 'lessons')).filter((f) => f.endsWith('.md') && f !== 'README.md');
    const index = await browser.newPage();
    await index.goto('file://' + path.join(site, 'index.html'));
    const links = await index.$$eval('li a', (as) => as.map((a) => a.getAttribute('href')));
    await index.close();
    assert.deepEqual(links, lessons.sort().map((f) => f.replace(/\.md$/, '.html')));
    for (const href of links) {
      const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
      const requests = [];
      page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) requests.push(r.url()); });
      await page.goto('file://' + path.join(site, href));
      await page.waitForSelector('body[data-ready="true"]', { timeout: 10000 });
      const n = await page.evaluate(() => window.raystep.data.lesson.steps.length);
      for (let k = 0; k < n; ++k) {
        if (k > 0) await page.keyboard.press('PageDown');
        // Every step shows a picture: its figure (the rendered picture, a curve, the tree, a report) or its walk,
        // and every inlined image decodes.
        const shown = await page.evaluate(() => ({
          figure: !document.getElementById('figure-side').hidden,
          walk: !document.body.classList.contains('no-walk'),
          images: Array.from(document.querySelectorAll('#figure-body img')).map((i) => i.complete && i.naturalWidth > 0),
        }));
        assert.ok(shown.figure || shown.walk, `${href} step ${k + 1}: a picture`);
        assert.ok(shown.images.every((ok) => ok), `${href} step ${k + 1}: its images decode`);
      }
      assert.equal(await page.textContent('#lesson-position'), `Step ${n} of ${n}`, href);
      assert.equal(await page.evaluate(() => document.body.dataset.error || ''), '', href);
      assert.deepEqual(requests, [], `${href}: the page asks the network for nothing`);
      assert.equal(await page.locator('h1').count(), 1, href);
      assert.ok((await page.textContent('#narration')).length > 0 || n === 1, `${href}: narration`);
      await page.close();
    }
    console.log(`ok site: ${links.length} lessons`);

    // Lesson 11's cost-curve question: the chart shows the curve but not the chosen plane until the answer.
    const page = await browser.newPage({ viewport: { width: 1280, height: 1100 } });
    await page.goto('file://' + path.join(site, '11-sah-build.html'));
    await page.waitForSelector('body[data-ready="true"]', { timeout: 10000 });
    const asked = await page.evaluate(() => window.raystep.data.lesson.steps.findIndex((s) => s.question));
    await page.evaluate((k) => window.raystep.lessonStep(k), asked);
    const chosen = page.locator('#figure-body .chosen').first();
    assert.equal(await chosen.evaluate((e) => getComputedStyle(e).visibility), 'hidden', 'the chosen plane waits');
    assert.ok(await page.locator('#figure-body [class^="candidate-"]').count() > 100, 'the candidates show');
    const right = await page.evaluate((k) => window.raystep.data.lesson.steps[k].question.choices.findIndex((c) => c.right),
                                      asked);
    await page.locator('#choices button').nth(right).click();
    assert.equal(await page.textContent('#verdict'), 'Right.');
    await page.screenshot({ path: path.join(out, 'player-lesson-11.png'), fullPage: true });
    assert.equal(await chosen.evaluate((e) => getComputedStyle(e).visibility), 'visible', 'then it shows');
    await page.close();
    console.log('ok lesson 11: the chart hides the chosen plane until the answer');
  } catch (e) {
    ++failures;
    console.error(`FAILED lesson site: ${e.message}`);
  }
} finally {
  await browser.close();
}
process.exit(failures ? 1 : 0);
