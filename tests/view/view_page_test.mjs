// `edgevio view`: the page of a finished run, opened from file:// in a real
// headless browser. It loads with no console error, shows one timeline entry
// per frames.csv row, draws the trajectory in 3D, shows the alignment
// picture of a clicked frame, and a screenshot of it is not blank.
// Usage: node view_page_test.mjs EDGEVIO_EXE WORK_DIR
import { readFileSync, rmSync, mkdirSync } from 'node:fs';
import { check, colourStats, edgevio, launch, watchedPage } from './browser.mjs';

const [exe, work] = process.argv.slice(2);
rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });
edgevio(exe, ['simulate', '--scenario', 'figure8', '--duration', '3', '--seed', '4', '--out', `${work}/data`]);
edgevio(exe, ['run', `${work}/data`, '--out', `${work}/run`]);
edgevio(exe, ['view', `${work}/run`]);
const rows = readFileSync(`${work}/run/frames.csv`, 'utf8').trim().split('\n').length - 1;

const browser = await launch();
try {
  const { page, errors } = await watchedPage(browser);
  await page.goto(`file://${work}/run/view.html`);
  await page.waitForFunction(n => document.querySelectorAll('#timeline .frame').length === n, rows, { timeout: 20000 });
  check(true, `the timeline shows ${rows} entries, one per frames.csv row`);
  // The 3D view drew the estimate: an orange line (#e8730c) at least a
  // quarter of the canvas wide (the view frames the whole path).
  const canvas = await page.evaluate(() => document.querySelector('#scene canvas').toDataURL('image/png').split(',')[1]);
  const scene = await colourStats(page, canvas);
  const canvasWidth = await page.evaluate(() => document.querySelector('#scene canvas').width);
  check(scene.orange > canvasWidth / 4, `the 3D view draws the estimate (${scene.orange} orange pixels, canvas ${canvasWidth} px wide)`);
  // A frame with a picture (a keyframe: the first frame is one) shows it.
  await page.click('#timeline .frame.keyframe');
  await page.waitForFunction(() => document.getElementById('picture').naturalWidth > 0, null, { timeout: 10000 });
  const width = await page.evaluate(() => document.getElementById('picture').naturalWidth);
  check(width === 376, `a keyframe's alignment picture is shown (${width} px wide: level 0 of a 752x480 camera)`);
  const row = await page.evaluate(() => document.querySelectorAll('#row-table tr').length);
  const columns = readFileSync(`${work}/run/frames.csv`, 'utf8').split('\n')[0].split(',').length;
  check(row === columns, `its frames.csv row is shown (${row} of ${columns} columns)`);
  const ate = await page.evaluate(() => document.querySelectorAll('#ate-plot polyline').length);
  check(ate === 1, 'the ATE over time is plotted');
  const shot = (await page.screenshot({ fullPage: true })).toString('base64');
  const stats = await colourStats(page, shot);
  // A blank page is one colour; text alone gives tens of anti-aliased shades;
  // the alignment picture and the plots give hundreds.
  check(stats.colours > 200 && stats.dominant < 0.9,
        `the screenshot is not blank (${stats.colours} colours, the commonest ${(100 * stats.dominant).toFixed(0)} %)`);
  check(errors.length === 0, `no console errors${errors.length ? `: ${errors.join('; ')}` : ''}`);
} finally {
  await browser.close();
}
