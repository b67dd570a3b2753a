// report_html_check.js - open the page `mpb report --format html` wrote in
// a real headless Chromium (every request but files refused), and follow
// its first link to a failed run's view. Used by test_report_html.sh.
//
//   node report_html_check.js REPORT.html PLOTS REPORT.json [SCREENSHOT.png]
//
// PLOTS is how many SVG plots the page must show. REPORT.json is what
// `mpb report --format json` wrote of the same database: every number of
// every table the browser renders must be its number, rounded to the
// decimals the page prints. Prints one "ok - ..." or "not ok - ..." line
// per check; exits 1 if any failed. SCREENSHOT.png, if given, gets the
// top of the page as a 1200 px wide window shows it (how
// docs/images/report-html.png is made).
'use strict';
const path = require('path');
const { chromium } = require(path.join(process.env.MPB_WEB_MODULES, 'playwright-core'));

const fs = require('fs');

const [report, plots, jsonPath, shotPath] = process.argv.slice(2);
const json = JSON.parse(fs.readFileSync(jsonPath, 'utf8'));

// The rows of the paper's table, by the label the page shows: which
// number of the JSON each holds (a metric's mean or sigma, or the success
// rate, a fraction there and a percentage here).
const ROWS = {
  'tau_t (Mean, s)': ['time_total', 'mean'],
  'tau_t (sigma, s)': ['time_total', 'sigma'],
  'tau_r (Mean, s)': ['time_raw', 'mean'],
  'tau_r (sigma, s)': ['time_raw', 'sigma'],
  'tau_o (Mean, s)': ['time_other', 'mean'],
  'tau_o (sigma, s)': ['time_other', 'sigma'],
  'world setup (Mean, s)': ['world_setup_time', 'mean'],
  'verify (Mean, s)': ['verify_time', 'mean'],
  'memory (Mean, MB)': ['memory', 'mean'],
  'd_n (Mean, m)': ['clearance', 'mean'],
  'd_n (sigma, m)': ['clearance', 'sigma'],
  'l_p (Mean, rad)': ['path_length', 'mean'],
  'l_p (sigma, rad)': ['path_length', 'sigma'],
  'l_e (Mean, m)': ['ee_path_length', 'mean'],
  'l_e (sigma, m)': ['ee_path_length', 'sigma'],
  "kappa' (Mean, rad^2)": ['smoothness', 'mean'],
  "kappa' (sigma, rad^2)": ['smoothness', 'sigma'],
  "kappa'_r (Mean, rad^2)": ['smoothness_resampled', 'mean'],
  "kappa'_r (sigma, rad^2)": ['smoothness_resampled', 'sigma'],
  'waypoints (Mean)': ['waypoints', 'mean'],
  'claimed s_r (%)': ['claimed_success_rate', null],
  's_r (%)': ['success_rate', null],
  // Claims in both directions: counts of runs (docs/metrics.md).
  'claimed': ['claimed_successes', null],
  'verified': ['outcomes', 'verified'],
  'refused claims': ['outcomes', 'refused'],
  'unclaimed valid': ['outcomes', 'unclaimed_valid'],
};

// Whether cell, as the page prints it, is x (a JSON number or null)
// rounded to the cell's own precision: "-" for null; "12.345" (fixed) or
// "1.23e-05" (three digits); a sigma may end with "*" (one query with one
// run). A value within a millionth of a unit of a tie may round either way
// (the JSON holds 15 digits, the page rounded the double).
function matches(cell, x, sigma) {
  if (sigma && cell.endsWith('*')) cell = cell.slice(0, -1);
  if (x === null) return cell === '-';
  if (Math.abs(x) < 1e-12) x = 0;   // the report's rounding noise
  const m = /^(-?)(\d+)(?:\.(\d+))?(?:e([+-]\d+))?$/.exec(cell);
  if (!m) return false;
  const digits = m[2] + (m[3] || ''), decimals = (m[3] || '').length;
  const shift = m[4] === undefined ? decimals : decimals - Number(m[4]);
  const scaled = Math.abs(x) * Math.pow(10, shift);
  const lo = Math.floor(scaled), frac = scaled - lo;
  const candidates = frac < 0.5 - 1e-6 ? [lo] : frac > 0.5 + 1e-6 ? [lo + 1] : [lo, lo + 1];
  const n = Number(digits);
  if (!candidates.includes(n)) return false;
  // The sign: C prints a negative value that rounds to 0 as -0.000.
  return n === 0 || (m[1] === '-') === (x < 0);
}

function checkTables(tables) {
  const bad = [];
  let cells = 0;
  if (tables.length !== json.scenes.length)
    bad.push(tables.length + ' tables for ' + json.scenes.length + ' scenes');
  for (const scene of json.scenes) {
    const t = tables.find((t) => t.scene === scene.name);
    if (!t) { bad.push('no table of scene ' + scene.name); continue; }
    if (t.runs !== scene.runs)
      bad.push(scene.name + ': ' + t.runs + ' finished runs, the JSON ' + scene.runs);
    const names = scene.planners.map((p) => p.name);
    if (JSON.stringify(t.header) !== JSON.stringify(names))
      bad.push(scene.name + ': columns ' + t.header.join(', ') + ', the JSON ' + names.join(', '));
    const shown = new Set();
    for (const row of t.rows) {
      const what = ROWS[row.label];
      if (!what) { bad.push(scene.name + ': a row the JSON has not: ' + row.label); continue; }
      shown.add(row.label);
      if (row.cells.length !== scene.planners.length)
        bad.push(scene.name + ', ' + row.label + ': ' + row.cells.length + ' cells');
      row.cells.forEach((cell, i) => {
        const p = scene.planners[i];
        if (!p) return;
        let x;
        if (what[0] === 'success_rate' || what[0] === 'claimed_success_rate')
          x = p[what[0]] === null ? null : 100 * p[what[0]];
        else if (what[0] === 'claimed_successes')
          x = p.runs > 0 ? p.claimed_successes : null;
        else if (what[0] === 'outcomes')
          x = p.runs > 0 ? p.outcomes[what[1]] : null;
        else
          x = p.metrics[what[0]][what[1]];
        cells++;
        if (!matches(cell, x, what[1] === 'sigma'))
          bad.push(scene.name + ', ' + row.label + ', ' + p.name + ': the page ' +
                   JSON.stringify(cell) + ', the JSON ' + x);
      });
    }
    // A metric the JSON has a mean of must have its row.
    for (const [label, what] of Object.entries(ROWS))
      if (what[1] === 'mean' && !shown.has(label) &&
          scene.planners.some((p) => p.metrics[what[0]].mean !== null))
        bad.push(scene.name + ': no row ' + label + ', which the JSON has');
    if (!shown.has('s_r (%)')) bad.push(scene.name + ': no success rate');
  }
  return { bad, cells };
}
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
  // The success-against-budget curves, drawn: each path of some length,
  // and some verified curve rising off the axis.
  const curves = await page.evaluate(() => Array.from(
    document.querySelectorAll('svg.budget path.curve')).map((p) => ({
      cls: p.getAttribute('class'), length: p.getTotalLength(),
      height: p.getBBox().height,
      width: p.getBoundingClientRect().width })));
  check('the budget curves are drawn (' + curves.length + ' paths)',
        curves.length > 0 && curves.every((c) => c.length > 0 && c.width > 100),
        JSON.stringify(curves));
  check('... a verified one rises', curves.some((c) => /verified/.test(c.cls) && c.height > 10));
  // The scenes' detail, folded away under sets: open, as a reader would.
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => { d.open = true; }));
  const shown = await page.evaluate(() => Array.from(document.querySelectorAll('.plots svg'))
    .filter((s) => s.getBoundingClientRect().width > 100).length);
  check('the report shows its ' + plots + ' plots', shown === Number(plots), 'shows ' + shown);
  check('no console errors in the report', errors.length === 0, errors.join('; '));
  // The tables as the browser renders them: per "Scene NAME" heading, the
  // count of finished runs and the next table, its header and cells.
  const tables = await page.evaluate(() => Array.from(document.querySelectorAll('h2'))
    .filter((h) => h.textContent.startsWith('Scene ')).map((h) => {
      let e = h.nextElementSibling, runs = null;
      while (e && e.tagName !== 'TABLE' && e.tagName !== 'H2') {
        const m = /^(\d+) finished runs?/.exec(e.textContent);
        if (m && runs === null) runs = Number(m[1]);
        e = e.nextElementSibling;
      }
      const rows = e && e.tagName === 'TABLE' ? Array.from(e.rows) : [];
      const text = (c) => c.innerText.trim();
      return {
        scene: h.textContent.slice('Scene '.length),
        runs,
        header: rows.length ? Array.from(rows[0].cells).slice(1).map(text) : [],
        rows: rows.slice(1).map((r) => ({
          label: text(r.cells[0]),
          cells: Array.from(r.cells).slice(1).map(text),
        })),
      };
    }));
  const t = checkTables(tables);
  check('every number of every table is the JSON report\'s (' + t.cells + ' cells)',
        t.bad.length === 0 && t.cells > 0, t.bad.join('; '));
  if (shotPath) {
    await page.screenshot({ path: shotPath, fullPage: true });
    check('a screenshot of the page', fs.statSync(shotPath).size > 10000);
  }
  const hrefs = await page.evaluate(() => Array.from(document.querySelectorAll('a[href]'))
    .map((a) => a.getAttribute('href')));
  const dead = hrefs.filter((h) => !/^[a-z]+:|^#/.test(h) &&
    !fs.existsSync(path.join(path.dirname(path.resolve(report)), h)));
  check('every link of the page names a file that is there (' + hrefs.length + ' links)',
        dead.length === 0 && hrefs.length > 0, 'missing: ' + dead.join(' '));
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
