// `edgevio run --realtime --view 0`: the live page in a real headless
// browser while a real-time run goes. Frames appear while the run is still
// going; at its end the page holds one timeline entry per frames.csv row,
// logged no console error, and a screenshot of it is not blank.
// Usage: node live_page_test.mjs EDGEVIO_EXE WORK_DIR
import { readFileSync, rmSync, mkdirSync } from 'node:fs';
import { spawn } from 'node:child_process';
import { check, colourStats, edgevio, launch, watchedPage } from './browser.mjs';

const [exe, work] = process.argv.slice(2);
rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });
edgevio(exe, ['simulate', '--scenario', 'figure8', '--duration', '6', '--seed', '6', '--out', `${work}/data`]);

const browser = await launch();
try {
  const { page, errors } = await watchedPage(browser);
  const run = spawn(exe, ['run', `${work}/data`, '--out', `${work}/run`, '--realtime', '--view', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let running = true;
  const exited = new Promise(resolve => run.on('exit', code => { running = false; resolve(code); }));
  const url = await new Promise((resolve, reject) => {
    let text = '';
    run.stderr.on('data', d => {
      text += d;
      const m = text.match(/viewer: (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (m) resolve(m[1]);
    });
    run.on('exit', () => reject(new Error(`the run ended before serving the viewer: ${text}`)));
  });
  await page.goto(url);
  // While the run goes: the timeline grows (the first count seen, and how many counts).
  let firstSeen = 0;
  const counts = new Set();
  while (running) {
    const n = await page.evaluate(() => document.querySelectorAll('#timeline .frame').length);
    if (running && n > 0) {
      if (!firstSeen) firstSeen = n;
      counts.add(n);
    }
    await new Promise(r => setTimeout(r, 100));
  }
  check(await exited === 0, 'the real-time run succeeded');
  await page.waitForFunction(() => document.body.dataset.ended === 'true', null, { timeout: 10000 });
  const rows = readFileSync(`${work}/run/frames.csv`, 'utf8').trim().split('\n').length - 1;
  check(firstSeen > 0 && firstSeen < rows && counts.size > 2,
        `frames appeared while the run went (first ${firstSeen} of ${rows}, then ${counts.size - 1} more counts)`);
  const shown = await page.evaluate(() => document.querySelectorAll('#timeline .frame').length);
  check(shown === rows, `the timeline shows ${shown} entries, one per frames.csv row (${rows})`);
  const pictured = await page.evaluate(() => document.querySelectorAll('#timeline .frame.picture').length);
  check(pictured > 0, `frames streamed with their alignment pictures (${pictured})`);
  const title = await page.evaluate(() => document.getElementById('title').textContent);
  check(title.includes('finished'), `the page says the run finished ("${title}")`);
  const shot = (await page.screenshot({ fullPage: true })).toString('base64');
  const stats = await colourStats(page, shot);
  check(stats.colours > 200 && stats.dominant < 0.9, `the screenshot is not blank (${stats.colours} colours)`);
  check(errors.length === 0, `no console errors${errors.length ? `: ${errors.join('; ')}` : ''}`);
} finally {
  await browser.close();
}
