// Shared by the viewer's browser tests: Debian's chromium driven by
// playwright-core (web/package.json), the checks every page must pass, and
// the programs the tests run. Exit status 77 (ctest's skip) when chromium
// or the npm packages are missing: scripts/setup.sh --test installs both.
import { createRequire } from 'node:module';
import { existsSync } from 'node:fs';
import { execFileSync } from 'node:child_process';

const require = createRequire(new URL('../../web/package.json', import.meta.url));

export const chromiumPath = process.env.EDGEVIO_CHROMIUM || '/usr/bin/chromium';

export function skip(why) {
  console.log(`SKIP: ${why} (scripts/setup.sh --test installs it)`);
  process.exit(77);
}

export function requirePackage(name) {
  try {
    return require(name);
  } catch {
    skip(`npm package ${name} not installed in web/node_modules`);
  }
}

export async function launch() {
  if (!existsSync(chromiumPath)) skip(`no chromium at ${chromiumPath}`);
  const { chromium } = requirePackage('playwright-core');
  // SwiftShader: WebGL on a machine without a GPU, as in CI.
  return chromium.launch({
    executablePath: chromiumPath,
    args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
  });
}

/// A page that records console errors and uncaught exceptions.
export async function watchedPage(browser) {
  const page = await browser.newPage({ viewport: { width: 1300, height: 1400 } });
  const errors = [];
  page.on('console', m => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', e => errors.push(`exception: ${e.message}`));
  return { page, errors };
}

/// The number of distinct colours in a PNG (as a base64 string), the share
/// of its most common colour, and how many pixels are orange (red well above
/// green and blue: the estimate's colour, blended with any background);
/// decoded by the browser itself.
export async function colourStats(page, pngBase64) {
  return page.evaluate(async png => {
    const img = new Image();
    img.src = `data:image/png;base64,${png}`;
    await img.decode();
    const canvas = new OffscreenCanvas(img.width, img.height);
    const ctx = canvas.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, img.width, img.height).data;
    const counts = new Map();
    let orange = 0;
    for (let i = 0; i < d.length; i += 4) {
      const c = (d[i] << 16) | (d[i + 1] << 8) | d[i + 2];
      counts.set(c, (counts.get(c) || 0) + 1);
      orange += d[i] > d[i + 1] + 40 && d[i + 1] > d[i + 2] + 20;
    }
    return { colours: counts.size, dominant: Math.max(...counts.values()) / (d.length / 4), orange };
  }, pngBase64);
}

/// Runs the edgevio program; throws with its output when it fails.
export function edgevio(exe, args) {
  return execFileSync(exe, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

export function check(ok, what) {
  if (!ok) throw new Error(`FAILED: ${what}`);
  console.log(`ok: ${what}`);
}
