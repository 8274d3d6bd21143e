#!/usr/bin/env node
// Opens simlab's pages in one headless Chromium (Debian's, through puppeteer-core), from disk, with no network, and
// runs axe-core's WCAG 2.0 and 2.1 rules of levels A and AA on each: every <details> opened, so that what it holds
// is checked too, in the light colour scheme and, for a page that has one (simlab's grade pages), the dark one.
//
//   node axe-check.js PAGE.html...
//
// Every page is opened with less motion asked for (prefers-reduced-motion), so that a replay waits to be played and
// draws no frame while axe reads it. The first replay page (simlab/replay.h; every replay runs the same script) is
// also worked from the keyboard alone: Tab reaches each of its controls, the 3-D view and its buttons, the chart and
// the table; End and Home on the time slider move the replay to its last and first instants; an arrow key on the
// focused 3-D view turns it, and its zoom button zooms it.
//
// Prints one line per page: the rules broken, each with the elements that break it, or "0 rules broken" with the
// number of rules that held. Exit 0 when no page breaks a rule; 1 when one does, or when a page, Chromium or the
// npm packages (scripts/install-deps installs them) cannot be had; 2 on a usage error.
"use strict";

const fs = require("fs");
const path = require("path");

const TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"];
const SCHEMES = ["light", "dark"];

function fail(message) {
  console.error("axe-check: error: " + message);
  process.exit(1);
}

let puppeteer, axeSource;
try {
  puppeteer = require("puppeteer-core");
  axeSource = require("axe-core").source;
} catch (e) {
  fail("the page checks' npm packages are not installed in " + __dirname + "/node_modules " +
       "(scripts/install-deps installs them with npm ci): " + String(e.message).split("\n")[0]);
}

function browserPath() {
  for (const candidate of [process.env.CHROMIUM, "/usr/bin/chromium", "/usr/bin/chromium-browser"]) {
    if (candidate && fs.existsSync(candidate)) return candidate;
  }
  return null;
}

// A line about the elements that break a rule: how many, and the first few by their CSS selector.
function elements(nodes) {
  const shown = nodes.slice(0, 4).map((n) => n.target.join(" ")).join(", ");
  return nodes.length + (nodes.length === 1 ? " element: " : " elements: ") + shown +
    (nodes.length > 4 ? ", ..." : "");
}

async function checkPage(browser, file, withKeys) {
  const page = await browser.newPage();
  const console_ = [];
  page.on("pageerror", (e) => console_.push(String(e.message).split("\n")[0]));
  try {
    // simlab's grade pages forbid scripts (Content-Security-Policy): axe's own is let in.
    await page.setBypassCSP(true);
    await page.setViewport({ width: 1200, height: 800 });
    // Nothing leaves the machine: a page that asks for anything but a file or a data URI is told no.
    await page.setRequestInterception(true);
    page.on("request", (r) => (/^(file|data|blob|about):/.test(r.url()) ? r.continue() : r.abort()));
    const url = "file://" + path.resolve(file);
    const results = {};
    const schemes = fs.readFileSync(file, "utf8").includes("prefers-color-scheme") ? SCHEMES : ["light"];
    for (const scheme of schemes) {
      // With less motion asked for, a replay waits to be played: no frame is drawn while axe reads the page.
      await page.emulateMediaFeatures([{ name: "prefers-color-scheme", value: scheme },
                                       { name: "prefers-reduced-motion", value: "reduce" }]);
      await page.goto(url, { waitUntil: "load", timeout: 60000 });
      // The replay pages draw their chart and tables from a script: let it run its first frames.
      await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
      await page.evaluate(() => document.querySelectorAll("details").forEach((d) => { d.open = true; }));
      await page.evaluate(axeSource);
      results[scheme] = await page.evaluate((tags) => window.axe.run(document, {
        runOnly: { type: "tag", values: tags },
        resultTypes: ["violations", "incomplete"],
      }), TAGS);
    }
    const keys = withKeys && (await page.$("#replay-data")) ? await replayKeys(page, url) : null;
    return { results, errors: console_, keys };
  } finally {
    await page.close();
  }
}

// The replay page's keyboard route (see the top of this file): the problems found, one line each.
async function replayKeys(page, url) {
  const problems = [];
  await page.emulateMediaFeatures([{ name: "prefers-color-scheme", value: "light" },
                                   { name: "prefers-reduced-motion", value: "reduce" }]);
  await page.goto(url + "#t=0", { waitUntil: "load", timeout: 60000 });
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  await page.evaluate(() => { document.getElementById("in-words").open = true; document.activeElement.blur(); });
  const reached = [];
  for (let i = 0; i < 20; ++i) {
    await page.keyboard.press("Tab");
    reached.push(await page.evaluate(() => {
      const e = document.activeElement;
      return e.id || e.getAttribute("aria-label") || (e.tagName === "SUMMARY" ? "summary" : e.tagName.toLowerCase());
    }));
  }
  const drawn = (await page.$("#view canvas")) !== null;  // no WebGL: no 3-D view to turn, nor its buttons
  for (const id of ["play", "speed", "time", "view"].concat(drawn ? ["turn left", "reset the view"] : [],
                                                             ["chart", "summary", "series-table"])) {
    if (!reached.includes(id)) problems.push("Tab never reaches #" + id + " (it reaches " + reached.join(", ") + ")");
  }
  const now = () => page.$eval("#now", (e) => e.textContent);
  await page.focus("#time");
  await page.keyboard.press("End");
  const end = await now();
  await page.keyboard.press("Home");
  const start = await now();
  if (end === start) problems.push("End and Home on the time slider leave it at " + start);
  if (drawn) {
    await page.focus("#view");
    const view = await page.$("#view");
    const before = await view.screenshot({ encoding: "base64" });
    await page.keyboard.press("ArrowLeft");
    await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
    const after = await view.screenshot({ encoding: "base64" });
    if (before === after) problems.push("ArrowLeft on the focused 3-D view does not turn it");
    await page.click("#view-turn button[data-key='+']");
    await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
    const zoomed = await view.screenshot({ encoding: "base64" });
    if (zoomed === after) problems.push("the zoom-in button does not zoom the 3-D view");
  }
  const rows = await page.$$eval("#series-table tbody tr", (r) => r.length);
  if (rows === 0) problems.push("the time series has no table");
  const words = await page.$eval("#motion", (e) => e.textContent.trim());
  if (!/^From t = /.test(words)) problems.push("the motion is not said in words: '" + words.slice(0, 60) + "'");
  return { problems, summary: "Tab reaches the play button, the speed, the time, the 3-D view and its buttons, the " +
    "chart and the table; End and Home move to " + end + " and back to " + start + "; an arrow key and a button " +
    "turn and zoom the view; the table has " + rows + " rows" };
}

async function main() {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error("usage: node axe-check.js PAGE.html...");
    process.exit(2);
  }
  for (const file of files) {
    if (!fs.existsSync(file)) fail(file + ": no such file");
  }
  const executablePath = browserPath();
  if (!executablePath) fail("chromium is not installed (scripts/install-deps installs it)");

  // The replays draw with WebGL: SwiftShader, Chromium's software GPU, asked for by name (tests/pages/page-check).
  const args = ["--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-quic",
                "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--hide-scrollbars"];
  if (process.getuid && process.getuid() === 0) args.push("--no-sandbox");
  const browser = await puppeteer.launch({ executablePath, headless: true, args, timeout: 60000 });
  let broken = 0, failed = 0, keysChecked = false;
  try {
    for (const file of files) {
      let checked;
      try {
        checked = await checkPage(browser, file, !keysChecked);
        keysChecked = keysChecked || checked.keys !== null;
      } catch (e) {
        console.log("axe-check: " + file + ": could not be checked: " + String(e.message).split("\n")[0]);
        ++failed;
        continue;
      }
      const rules = new Map();  // rule id -> the line said of it, per scheme
      let held = 0, review = 0;
      const schemes = Object.keys(checked.results);
      for (const scheme of schemes) {
        const r = checked.results[scheme];
        held = Math.max(held, r.passes ? r.passes.length : 0);
        review += r.incomplete.length;
        for (const v of r.violations) {
          const line = v.id + " (" + v.impact + ", " + v.tags.filter((t) => TAGS.includes(t)).join(" ") + "): " +
            v.help + ": " + elements(v.nodes);
          const seen = rules.get(v.id) || { line, schemes: [] };
          seen.schemes.push(scheme);
          rules.set(v.id, seen);
        }
      }
      for (const e of checked.errors) console.log("axe-check: " + file + ": the page's script failed: " + e);
      if (checked.errors.length > 0) ++failed;
      if (checked.keys) {
        for (const p of checked.keys.problems) console.log("axe-check: " + file + ": keyboard: " + p);
        if (checked.keys.problems.length > 0) ++failed;
        else console.log("axe-check: " + file + ": keyboard: " + checked.keys.summary);
      }
      if (rules.size === 0) {
        console.log("axe-check: " + file + ": 0 rules broken (" + schemes.join(" and ") + ")" +
                    (review ? "; " + review + " results axe leaves to a person" : ""));
        if (process.env.AXE_CHECK_REVIEW) {
          for (const scheme of schemes) {
            for (const r of checked.results[scheme].incomplete) {
              console.log("  to review (" + scheme + "): " + r.id + ": " + r.help + ": " + elements(r.nodes));
            }
          }
        }
        continue;
      }
      broken += rules.size;
      console.log("axe-check: " + file + ": " + rules.size + (rules.size === 1 ? " rule" : " rules") + " broken");
      for (const [, v] of rules) console.log("  " + v.line + " [" + v.schemes.join(", ") + "]");
    }
  } finally {
    await browser.close();
  }
  console.log("axe-check: " + files.length + (files.length === 1 ? " page" : " pages") + ", " + broken +
              (broken === 1 ? " rule" : " rules") + " broken (axe-core " + require("axe-core").version +
              ", tags " + TAGS.join(" ") + ")");
  process.exit(broken > 0 || failed > 0 ? 1 : 0);
}

main().catch((e) => fail(String(e.message || e).split("\n")[0]));
