// report_html_check.js - open the page `mpb report --format html` wrote in
// a real headless Chromium (every request but files refused), and follow
// its first link to a failed run's view. Used by test_report_html.sh.
//
//   node report_html_check.js REPORT.html PLOTS
//
// PLOTS is how many SVG plots the page must show. Prints one "ok - ..." or
// "not ok - ..." line per check; exits 1 if any failed.
'use strict';
const path = require('path');
const { chromium } = require(path.join(process.env.MPB_WEB_MODULES, 'playwright-core'));

const [report, plots] = process.argv.slice(2);
let failed = 0;
function check(name, ok, detail) {
  if (!ok) failed++;
  console.log((ok ? 'ok - ' : 'not ok - ') + name + (ok || !detail ? '' : ' (' + detail + ')'));
}

(async () => {
  const browser = await chromium.launch({
    executablePath: process.env.MPB_CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update',
           '--disable-sync'],
  });
  const context = await browser.newContext({ viewport: { width: 1200, height: 800 } });
  const requests = [];
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (/^(file|blob|data):/.test(url)) return route.continue();
    requests.push(url);
    return route.abort();
  });
  const page = await context.newPage();
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto('file://' + path.resolve(report));
  const shown = await page.evaluate(() => Array.from(document.querySelectorAll('.plots svg'))
    .filter((s) => s.getBoundingClientRect().width > 100).length);
  check('the report shows its ' + plots + ' plots', shown === Number(plots), 'shows ' + shown);
  check('no console errors in the report', errors.length === 0, errors.join('; '));
  const link = page.locator('a[href^="views/run-"]').first();
  check('it links a failed run', await link.count() === 1);
  await link.click();
  let ready = false;
  for (let i = 0; i < 600 && !ready && errors.length === 0; i++) {
    ready = await page.evaluate(() => document.body.dataset.ready === '1').catch(() => false);
    if (!ready) await new Promise((r) => setTimeout(r, 100));
  }
  check('the link opens the run\'s 3-D view, drawn', ready, errors.join('; '));
  check('no console errors there either', errors.length === 0, errors.join('; '));
  check('nothing asked of the network', requests.length === 0, requests.join(' '));
  await browser.close();
  process.exit(failed ? 1 : 0);
})().catch((e) => {
  console.log('not ok - the browser ran the checks (' + e.message.split('\n')[0] + ')');
  process.exit(1);
});
