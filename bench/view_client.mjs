// For bench/viewer_cost.sh: `edgevio run DATA --out OUT --view 0` watched by
// Debian's headless chromium from the first frame to the end.
// Usage: node view_client.mjs EDGEVIO_EXE DATA OUT
import { spawn } from 'node:child_process';
import { launch, watchedPage } from '../tests/view/browser.mjs';

const [exe, data, out] = process.argv.slice(2);
const browser = await launch();
try {
  const { page } = await watchedPage(browser);
  const run = spawn(exe, ['run', data, '--out', out, '--view', '0'], { stdio: ['ignore', 'ignore', 'pipe'] });
  const exited = new Promise(resolve => run.on('exit', resolve));
  const url = await new Promise(resolve => {
    let text = '';
    run.stderr.on('data', d => {
      text += d;
      const m = text.match(/viewer: (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (m) resolve(m[1]);
    });
  });
  await page.goto(url);
  await page.waitForFunction(() => document.body.dataset.ended === 'true', null, { timeout: 0 });
  if (await exited !== 0) process.exit(1);
} finally {
  await browser.close();
}
