#!/usr/bin/env node
// study_browser.mjs: takes the web study (`cbtl study serve`, docs/study-api.md) in a real browser, headless
// Chromium driven through playwright-core, as participant browser-1 on a phone-sized screen, and then checks what
// the database holds (`cbtl study export`, `cbtl study analyze`).
//
//   node tests/browser/study_browser.mjs --cbtl build/bin/cbtl --program domains/feeding/feeding.cbtl \
//        --artifacts build/study-browser
//
// Along the way: keyboard-only consent and first rating, declining consent records nothing, every page's heading
// takes focus and nothing scrolls sideways at 390 px, every picture loads, the server restarted between meals
// 2 and 3 continues at meal 3, a lost answer is resent and "replayed", a refused record shows the server's
// message and keeps the answer, a wrong trial index is a 409 with a JSON error. Screenshots of each page kind go
// to --artifacts. Exit status 0 when every check passed.
import {chromium} from 'playwright-core';
import {spawn, spawnSync} from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import readline from 'node:readline';
import {isDeepStrictEqual, parseArgs} from 'node:util';

const PARTICIPANT = 'browser-1';
const VIEWPORT = {width: 390, height: 844};
const PAGES = 13;
const LISTEN_TIMEOUT_MS = 60_000;
// A page change may wait for the server to solve the next meal or render pictures: be generous.
const PAGE_TIMEOUT_MS = 180_000;
const CHROMIUM_ARGS = ['--headless=new', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// What the participant answers, meal by meal. Each answer picks from the page's own choices (so the script does
// not depend on the menu), and the answers differ from meal to meal.
const MEAL_SCRIPT = [
  {likert: 4, dip: (s) => s.context.sauces[0], signal: 0, verbosity: 1, blocked: (i) => i % 2 === 0},
  {likert: 2, dip: (s) => s.choices.dip[1], signal: 1, verbosity: 0, blocked: () => false},
  {likert: 5, dip: (s) => s.choices.dip[s.choices.dip.length - 1], signal: 2, verbosity: 2, blocked: () => true},
  {likert: 1, dip: (s) => s.choices.dip[0], signal: 1, verbosity: 2, blocked: (i) => i % 2 === 1},
  {likert: 3, dip: (s) => s.choices.dip[1], signal: 0, verbosity: 1, blocked: () => false},
];
const DEMOGRAPHICS = {age: 34, gender: 'other', gender_other: 'genderfluid', robot_experience: true,
  fed_experience: false};
const COMMENTS = 'The pictures were clear. Typed by the browser test.';

class TestFailure extends Error {}

function fail(message) {
  throw new TestFailure(message);
}

function check(condition, message) {
  if (!condition) fail(message);
}

// Failures that should not stop the run (so that everything after them is still checked), reported at the end.
const laterFailures = [];

function checkLater(condition, message) {
  if (!condition && !laterFailures.includes(message)) {
    console.log(`[test] problem (reported at the end): ${message}`);
    laterFailures.push(message);
  }
}

function log(...parts) {
  console.log('[test]', ...parts);
}

function sleep(ms) {
  return new Promise((resolve) => setTimeout(resolve, ms));
}

function parseCommandLine() {
  const {values} = parseArgs({options: {
    cbtl: {type: 'string'}, program: {type: 'string'}, artifacts: {type: 'string'},
  }});
  for (const name of ['cbtl', 'program', 'artifacts']) {
    if (!values[name]) {
      console.error('usage: node study_browser.mjs --cbtl <cbtl> --program <feeding.cbtl> --artifacts <dir>');
      process.exit(2);
    }
  }
  return {cbtl: path.resolve(values.cbtl), program: path.resolve(values.program),
    artifacts: path.resolve(values.artifacts)};
}

// ---------------------------------------------------------------------------------------------------------------
// The server: `cbtl study serve` as a child process, its output passed through with a prefix.

class StudyServer {
  constructor(cbtl, program, db) {
    this.cbtl = cbtl;
    this.program = program;
    this.db = db;
    this.child = null;
    this.exited = null;  // a promise of {code, signal}
  }

  // Starts the server on `port` (0: any free port) and resolves to its URL once it printed its first line,
  // "listening on http://127.0.0.1:<port>/".
  start(port = 0) {
    const args = ['study', 'serve', this.program, '--port', String(port), '--db', this.db];
    log(`starting: ${this.cbtl} ${args.join(' ')}`);
    const child = spawn(this.cbtl, args, {stdio: ['ignore', 'pipe', 'pipe']});
    this.child = child;
    this.exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve({code, signal})));
    const stderrTail = [];
    readline.createInterface({input: child.stderr}).on('line', (line) => {
      console.log(`[server stderr] ${line}`);
      stderrTail.push(line);
      if (stderrTail.length > 20) stderrTail.shift();
    });
    return new Promise((resolve, reject) => {
      let first = true;
      const timer = setTimeout(() => {
        reject(new TestFailure(`the server printed no "listening on" line within ${LISTEN_TIMEOUT_MS / 1000} s`));
        this.stop();
      }, LISTEN_TIMEOUT_MS);
      readline.createInterface({input: child.stdout}).on('line', (line) => {
        console.log(`[server] ${line}`);
        if (!first) return;
        first = false;
        clearTimeout(timer);
        const match = /^listening on (http:\/\/127\.0\.0\.1:(\d+)\/)\s*$/.exec(line);
        if (match) resolve({url: match[1], port: Number(match[2])});
        else reject(new TestFailure(`the server's first line is not "listening on http://127.0.0.1:<port>/": ${line}`));
      });
      child.on('error', (error) => {
        clearTimeout(timer);
        reject(new TestFailure(`cannot start ${this.cbtl}: ${error.message}`));
      });
      this.exited.then(({code, signal}) => {
        clearTimeout(timer);
        if (first) {
          reject(new TestFailure(`the server exited (${signal || `status ${code}`}) before listening:\n` +
            stderrTail.join('\n')));
        }
      });
    });
  }

  // SIGTERM, then SIGKILL if it has not exited 20 s later. Resolves to how it exited.
  async stop() {
    const child = this.child;
    if (!child || child.exitCode !== null || child.signalCode !== null) return this.exited;
    child.kill('SIGTERM');
    const timeout = sleep(20_000).then(() => null);
    const how = await Promise.race([this.exited, timeout]);
    if (how) return how;
    log('the server did not exit within 20 s of SIGTERM: killing it');
    child.kill('SIGKILL');
    return this.exited;
  }
}

// Stops the server and insists on a clean exit: 0, or death by the SIGTERM itself.
async function stopCleanly(server) {
  const {code, signal} = await server.stop();
  log(`server stopped (${signal ? `signal ${signal}` : `exit status ${code}`})`);
  check(code === 0 || signal === 'SIGTERM', `the server did not stop cleanly on SIGTERM (${signal || code})`);
}

// Restarts on the same port, so that the page's origin (and with it the tab's sessionStorage, which holds the
// start of elapsed_ms) stays the same. A port just released may take a moment to be free again.
async function restartOnPort(server, port) {
  const deadline = Date.now() + 30_000;
  for (;;) {
    try {
      return await server.start(port);
    } catch (error) {
      if (Date.now() > deadline) fail(`cannot restart the server on port ${port}: ${error.message}`);
      log(`restart on port ${port} failed (${error.message.split('\n')[0]}); trying again`);
      await sleep(1000);
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// The page.

class Browser {
  constructor(page) {
    this.page = page;
    this.pageErrors = [];
    this.foreignRequests = [];
    this.origin = '';
    page.on('console', (message) => console.log(`[browser ${message.type()}] ${message.text()}`));
    page.on('pageerror', (error) => {
      console.log(`[browser page error] ${error.message}`);
      this.pageErrors.push(error.message);
    });
    // The pages may load nothing but the server's own files (pictures are shown from blob: copies of them).
    page.on('request', (request) => {
      const url = request.url();
      const own = url.startsWith(this.origin) || url.startsWith(`blob:${this.origin}`) || url.startsWith('data:');
      if (!own) this.foreignRequests.push(url);
    });
  }

  checkHealthy(where) {
    check(this.pageErrors.length === 0, `${where}: page error(s): ${this.pageErrors.join('; ')}`);
    check(this.foreignRequests.length === 0,
      `${where}: the page fetched from elsewhere than the server: ${this.foreignRequests.join(', ')}`);
  }

  // The participant's state, asked from inside the page (same origin, as the page's own script asks), with the
  // key the page keeps in its address (#key=...).
  async apiState() {
    return this.page.evaluate(async (id) => {
      const key = (/#key=([0-9a-f]{64})/.exec(location.hash) || [])[1];
      if (!key) return {error: `the page's address holds no key: ${location.href}`};
      const response = await fetch(`/api/participants/${id}`,
        {cache: 'no-store', headers: {Authorization: `Bearer ${key}`}});
      return response.json();
    }, PARTICIPANT);
  }

  // Waits until the page shows `kind` as page `trial + 1`, then checks what every page must do: focus on the
  // heading, the progress line, no sideways scrolling, no page errors; and that the server agrees on the page.
  async expectPage(kind, trial, meal = 0) {
    const expectedProgress = kind === 'done' ? null : `Page ${trial + 1} of ${PAGES}`;
    await this.page.waitForFunction(([k, p]) => {
      const main = document.querySelector('main');
      const progress = document.getElementById('progress').textContent;
      return main.dataset.page === k && (p === null || progress === p);
    }, [kind, expectedProgress], {timeout: PAGE_TIMEOUT_MS});
    const where = `${kind} (page ${trial + 1}${meal ? `, meal ${meal}` : ''})`;
    const focus = await this.page.evaluate(() => {
      const active = document.activeElement;
      return {tag: active && active.tagName, inMain: !!(active && active.closest('main'))};
    });
    check(focus.tag === 'H1' && focus.inMain, `${where}: focus is on ${focus.tag}, not on the page's heading`);
    await this.checkNoSidewaysScroll(where);
    this.checkHealthy(where);
    const state = await this.apiState();
    check(state.page === kind && state.next_trial === trial && (state.meal ?? 0) === meal,
      `${where}: the server's state says page ${state.page}, trial ${state.next_trial}, meal ${state.meal}`);
    log(`${kind === 'done' ? 'after the last page' : `page ${trial + 1}`}: ${kind}${meal ? ` (meal ${meal})` : ''}`);
    return state;
  }

  async checkNoSidewaysScroll(where) {
    const widths = await this.page.evaluate(() =>
      ({scroll: document.scrollingElement.scrollWidth, inner: window.innerWidth}));
    check(widths.scroll <= widths.inner,
      `${where}: the page scrolls sideways (scrollWidth ${widths.scroll} > innerWidth ${widths.inner})`);
  }

  continueButton() {
    return this.page.locator('main form button[type="submit"]');
  }

  async expectContinue(enabled, where) {
    const disabled = await this.continueButton().isDisabled();
    check(disabled === !enabled, `${where}: Continue is ${disabled ? 'disabled' : 'enabled'}; expected the opposite`);
  }

  async focusedDescription() {
    return this.page.evaluate(() => {
      const a = document.activeElement;
      return a ? `${a.tagName.toLowerCase()}${a.name ? `[name=${a.name}]` : ''}${a.value ? `[value=${a.value}]` : ''}`
        : 'nothing';
    });
  }

  async expectFocus(description, where) {
    const focused = await this.focusedDescription();
    check(focused === description, `${where}: focus is on ${focused}, expected ${description}`);
  }

  async screenshot(artifacts, name) {
    const file = path.join(artifacts, name);
    await this.page.screenshot({path: file, fullPage: true});
    log(`screenshot ${file}`);
  }

  async pick(name, value) {
    await this.page.locator(`main input[type="radio"][name="${name}"][value="${value}"]`).check();
  }
}

// ---------------------------------------------------------------------------------------------------------------
// The study, page by page. `expected` collects each record as the database should hold it.

async function consentPages(b, artifacts, expected) {
  let state = await b.expectPage('consent', 0);
  check(state.next_trial === 0, 'a new participant does not start at trial 0');
  await b.screenshot(artifacts, 'consent.png');
  await b.expectContinue(false, 'consent');

  // Declining stores nothing and says the window may be closed; "I changed my mind" comes back.
  await b.pick('consent', 'decline');
  await b.continueButton().click();
  await b.page.waitForSelector('main[data-page="declined"]');
  const text = await b.page.textContent('main');
  check(/close this window/i.test(text), `the declined page does not say the window may be closed: ${text}`);
  state = await b.apiState();
  check(state.next_trial === 0, `declining stored something: the state is at trial ${state.next_trial}`);
  await b.page.getByRole('button', {name: 'I changed my mind'}).click();
  await b.expectPage('consent', 0);

  // Agreeing with the keyboard alone: from the focused heading, Tab reaches the group, Space picks "I agree",
  // Tab reaches Continue, Enter sends it.
  await b.page.keyboard.press('Tab');
  await b.expectFocus('input[name=consent][value=agree]', 'consent (keyboard)');
  await b.page.keyboard.press('Space');
  await b.page.keyboard.press('Tab');
  await b.expectFocus('button', 'consent (keyboard)');
  await b.expectContinue(true, 'consent');
  await b.page.keyboard.press('Enter');
  expected.push({kind: 'consent', meal: 0, response: {agree: true}});
}

async function demographicsPage(b, artifacts, expected) {
  await b.expectPage('demographics', 1);
  await b.screenshot(artifacts, 'demographics.png');
  const where = 'demographics';
  await b.expectContinue(false, where);
  const age = b.page.getByLabel('Your age in years');
  const other = b.page.locator('main input[name="gender-other"]');
  check(await other.isDisabled(), `${where}: the "other" text field is enabled before Other is chosen`);

  await age.fill('17');  // below the range: not an answer
  await b.pick('gender', DEMOGRAPHICS.gender);
  check(await other.isEnabled(), `${where}: the "other" text field stays disabled with Other chosen`);
  await other.fill(DEMOGRAPHICS.gender_other);
  await b.pick('robot', DEMOGRAPHICS.robot_experience ? 'yes' : 'no');
  await b.pick('fed', DEMOGRAPHICS.fed_experience ? 'yes' : 'no');
  await b.expectContinue(false, `${where} with age 17`);
  await age.fill(String(DEMOGRAPHICS.age));
  await b.expectContinue(true, where);
  await b.continueButton().click();
  expected.push({kind: 'demographics', meal: 0, response: {...DEMOGRAPHICS}});
}

// The rating page's content against the state: the meal in words and both options.
async function checkRatingContent(b, state) {
  const where = `rating (meal ${state.meal})`;
  // Two options that would feed alike get a word of why (meal 1: nothing is learned yet).
  const same = state.options.length === 2 && state.options.every((o) => o.solved) &&
    ['dip', 'signal', 'verbosity'].every((k) => state.options[0][k] === state.options[1][k]);
  const main = await b.page.textContent('main');
  check(same === main.includes('The two options are the same this time'),
    `${where}: options ${same ? 'alike without' : 'different with'} the explanation`);

  const heading = await b.page.textContent('main h1');
  check(heading.startsWith(`Meal ${state.meal} of ${state.meals}:`) && heading.includes(state.context.food),
    `${where}: the heading does not describe the meal: "${heading}"`);
  for (const option of state.options) {
    const card = b.page.locator(`main section.option[aria-label="Option ${option.label}"]`);
    check(await card.count() === 1, `${where}: Option ${option.label} is not shown`);
    const text = await card.textContent();
    if (!option.solved) {
      check(/no plan/i.test(text), `${where}: unsolved Option ${option.label} does not say so: ${text}`);
      continue;
    }
    for (const key of ['dip', 'signal', 'verbosity']) {
      const shown = (state.labels && state.labels[option[key]]) || option[key];
      check(text.includes(shown), `${where}: Option ${option.label} does not show its ${key} "${shown}": ${text}`);
    }
  }
}

// how: 'keyboard' (Tab, Space, arrows, Enter), 'click', or 'refused' (clicks; the first record sent is refused by
// the server, withRefusedRecord, and the participant sends it again).
async function ratingPage(b, artifacts, expected, meal, how) {
  const trial = 2 * meal;
  const where = `rating (meal ${meal})`;
  const state = await b.expectPage('rating', trial, meal);
  await checkRatingContent(b, state);
  await b.expectContinue(false, where);
  if (meal === 1) await b.screenshot(artifacts, 'rating.png');
  const likert = MEAL_SCRIPT[meal - 1].likert;
  if (how === 'keyboard') {
    // Tab from the heading into the scale, Space picks its first point, arrow keys move to the scripted one.
    await b.page.keyboard.press('Tab');
    await b.expectFocus('input[name=likert][value=1]', `${where}, keyboard`);
    await b.page.keyboard.press('Space');
    for (let v = 1; v < likert; v++) await b.page.keyboard.press('ArrowDown');
    await b.expectFocus(`input[name=likert][value=${likert}]`, `${where}, keyboard`);
    await b.page.keyboard.press('Tab');
    await b.expectFocus('button', `${where}, keyboard`);
    await b.expectContinue(true, where);
    await b.page.keyboard.press('Enter');
  } else {
    await b.pick('likert', String(likert));
    await b.expectContinue(true, where);
    if (how === 'refused') await withRefusedRecord(b, where, () => b.continueButton().click());
    await b.continueButton().click();
  }
  expected.push({kind: 'rating', meal, response: {likert}});
}

async function answersPage(b, artifacts, expected, meal) {
  const trial = 2 * meal + 1;
  const state = await b.expectPage('answers', trial, meal);
  const where = `answers (meal ${meal})`;
  const heading = await b.page.textContent('main h1');
  check(heading.startsWith(`Meal ${meal} of ${state.meals}:`), `${where}: the heading does not name the meal`);

  // Every picture loaded, with alt text.
  const views = state.views || [];
  await b.page.waitForFunction(() => [...document.querySelectorAll('main img')].every((img) => img.complete),
    null, {timeout: PAGE_TIMEOUT_MS});
  const images = await b.page.$$eval('main img', (imgs) => imgs.map((img) => {
    // The widest spread of any colour channel over the picture's pixels: 0 for a picture of one flat colour
    // (an offscreen renderer that drew nothing gives an all-black picture that still "loads").
    let spread = 0;
    if (img.naturalWidth > 0) {
      const canvas = document.createElement('canvas');
      canvas.width = img.naturalWidth;
      canvas.height = img.naturalHeight;
      const context = canvas.getContext('2d');
      context.drawImage(img, 0, 0);
      const pixels = context.getImageData(0, 0, canvas.width, canvas.height).data;
      for (let channel = 0; channel < 3; channel++) {
        let low = 255;
        let high = 0;
        for (let i = channel; i < pixels.length; i += 4) {
          low = Math.min(low, pixels[i]);
          high = Math.max(high, pixels[i]);
        }
        spread = Math.max(spread, high - low);
      }
    }
    return {src: img.getAttribute('src'), width: img.naturalWidth, height: img.naturalHeight, alt: img.alt, spread};
  }));
  check(images.length === views.length, `${where}: ${images.length} pictures shown, the state has ${views.length}`);
  // The question says what the arm could block: the TV, the friend, or (alone) the table and the plate.
  const questions = await b.page.locator('main section.picture legend, main section.picture .question').allTextContents();
  const what = {withFriendAndTv: 'your friend or of the TV', withFriend: 'your friend', withTv: 'the TV',
    alone: 'the table and your plate'}[state.context.setting];
  check(views.length === 0 || (await b.page.textContent('main')).includes(`block your view of ${what}`),
    `${where}: the picture question does not say what is blocked (${state.context.setting}): ${questions}`);
  for (const image of images) {
    check(image.width > 0, `${where}: the picture ${image.src} did not load`);
    check(image.alt.trim().length > 0, `${where}: the picture ${image.src} has no alt text`);
    // Not fatal at once, so that the rest of the study is still checked; reported at the end.
    checkLater(image.spread > 8, `${where}: the picture ${image.src} (${image.width}x${image.height}) is one ` +
      'flat colour: nothing was drawn');
  }
  await b.checkNoSidewaysScroll(`${where} with its pictures`);
  await b.expectContinue(false, where);

  const script = MEAL_SCRIPT[meal - 1];
  const response = {
    dip: script.dip(state),
    signal: state.choices.signal[script.signal],
    verbosity: state.choices.verbosity[script.verbosity],
    blocked: views.map((url, i) => script.blocked(i)),
  };
  await b.pick('dip', response.dip);
  await b.pick('signal', response.signal);
  await b.pick('verbosity', response.verbosity);
  for (const [i, blocked] of response.blocked.entries()) await b.pick(`blocked-${i}`, blocked ? 'yes' : 'no');
  await b.expectContinue(true, where);
  if (meal === 1) await b.screenshot(artifacts, 'answers.png');
  await b.continueButton().click();
  expected.push({kind: 'answers', meal, response});
}

// A wrong trial index, sent from the page as any script could: 409 and a JSON error; the session is unchanged.
async function checkWrongTrialIndex(b) {
  const before = await b.apiState();
  const answer = await b.page.evaluate(async ([id, trial]) => {
    const key = (/#key=([0-9a-f]{64})/.exec(location.hash) || [])[1];
    const response = await fetch(`/api/participants/${id}/records`, {
      method: 'POST', headers: {'Content-Type': 'application/json', Authorization: `Bearer ${key}`},
      body: JSON.stringify({trial_index: trial + 2, kind: 'rating', meal: 4, elapsed_ms: 1, rt_ms: 1,
        response: {likert: 3}}),
    });
    return {status: response.status, type: response.headers.get('Content-Type'), body: await response.text()};
  }, [PARTICIPANT, before.next_trial]);
  log(`a record with trial index ${before.next_trial + 2} instead of ${before.next_trial}: HTTP ${answer.status} ` +
    answer.body);
  check(answer.status === 409, `a wrong trial index was answered HTTP ${answer.status}, not 409`);
  let error;
  try {
    error = JSON.parse(answer.body).error;
  } catch (e) {
    fail(`the 409 answer is not JSON: ${answer.body}`);
  }
  check(typeof error === 'string' && error.trim().length > 0, `the 409 answer has no "error" message: ${answer.body}`);
  const after = await b.apiState();
  check(after.next_trial === before.next_trial, 'a refused record changed the session');
}

// The answer to the first record request is lost on its way back (the server did store it): the page must send
// the same body again, which the server answers "replayed", and go on.
async function withLostAnswer(b, action) {
  const recordsUrl = `**/api/participants/${PARTICIPANT}/records`;
  const bodies = [];
  let lostStatus = null;
  await b.page.route(recordsUrl, async (route) => {
    bodies.push(route.request().postData());
    if (bodies.length === 1) {
      const response = await route.fetch();
      lostStatus = (await response.json()).status;
      await route.abort('connectionreset');
    } else {
      await route.continue();
    }
  });
  // Only a response to the resent request counts (bodies holds both by then).
  const resent = b.page.waitForResponse((r) => r.url().endsWith('/records') && bodies.length === 2,
    {timeout: PAGE_TIMEOUT_MS});
  await action();
  const answer = await (await resent).json();
  await b.page.unroute(recordsUrl);
  log(`lost answer: the server had ${lostStatus} the record; the resent one was ${answer.status}`);
  check(lostStatus === 'stored', `the first request was not stored (${lostStatus})`);
  check(bodies.length === 2 && bodies[0] === bodies[1], 'the page did not resend the very same body');
  check(answer.status === 'replayed', `the resent record was answered "${answer.status}", not "replayed"`);
}

// The first record request reaches the server with a wrong trial index: the page must show the server's message
// in its alert region, keep the answer and let the participant send it again.
async function withRefusedRecord(b, where, action) {
  const recordsUrl = `**/api/participants/${PARTICIPANT}/records`;
  await b.page.route(recordsUrl, async (route) => {
    const body = JSON.parse(route.request().postData());
    await route.continue({postData: JSON.stringify({...body, trial_index: body.trial_index + 2})});
  }, {times: 1});
  const refused = b.page.waitForResponse((r) => r.url().endsWith('/records'), {timeout: PAGE_TIMEOUT_MS});
  await action();
  const response = await refused;
  const error = (await response.json()).error;
  log(`refused record: HTTP ${response.status()} ${error}`);
  check(response.status() >= 400, `the tampered record was accepted (HTTP ${response.status()})`);
  const alert = b.page.locator('[role="alert"]');
  await alert.waitFor({state: 'visible'});
  const shown = await alert.textContent();
  check(shown.includes(error), `${where}: the alert does not show the server's message: "${shown}"`);
  check(await b.page.locator('main input[name="likert"]:checked').count() === 1,
    `${where}: the answer was lost after the error`);
  await b.expectContinue(true, `${where} after the error`);
  await b.page.unroute(recordsUrl);
}

async function completePages(b, artifacts, expected) {
  await b.expectPage('complete', 12);
  await b.screenshot(artifacts, 'complete.png');
  await b.expectContinue(true, 'complete (comments are optional)');
  await b.page.getByLabel('Comments (optional)').fill(COMMENTS);
  await b.page.getByRole('button', {name: 'Submit'}).click();
  expected.push({kind: 'complete', meal: 0, response: {comments: COMMENTS}});

  await b.expectPage('done', 13);
  await b.screenshot(artifacts, 'done.png');
  check(await b.page.locator('main button, main input, main textarea').count() === 0,
    'the done page still asks for something');
  await b.page.reload();
  await b.expectPage('done', 13);
}

async function takeStudy(b, server, artifacts, expected) {
  await consentPages(b, artifacts, expected);
  await demographicsPage(b, artifacts, expected);
  for (let meal = 1; meal <= 5; meal++) {
    if (meal === 3) {
      // A restarted server continues where the participant was: meal 3's rating page.
      await b.expectPage('rating', 6, 3);
      const port = Number(new URL(b.origin).port);
      await stopCleanly(server);
      await restartOnPort(server, port);
      await b.page.reload();
      await b.expectPage('rating', 6, 3);
      await checkWrongTrialIndex(b);
    }
    if (meal === 1) await ratingPage(b, artifacts, expected, meal, 'keyboard');
    else if (meal === 4) {
      // Once the page is there, so that no earlier request is still under way when the route is set.
      await b.expectPage('rating', 8, 4);
      await withLostAnswer(b, () => ratingPage(b, artifacts, expected, meal, 'click'));
    }
    else if (meal === 5) await ratingPage(b, artifacts, expected, meal, 'refused');
    else await ratingPage(b, artifacts, expected, meal, 'click');
    await answersPage(b, artifacts, expected, meal);
  }
  await completePages(b, artifacts, expected);
}

// ---------------------------------------------------------------------------------------------------------------
// The database, through the commands the analysis uses.

function run(cbtl, args) {
  log(`running: ${cbtl} ${args.join(' ')}`);
  const result = spawnSync(cbtl, args, {encoding: 'utf8', maxBuffer: 64 * 1024 * 1024});
  if (result.error) fail(`cannot run ${cbtl}: ${result.error.message}`);
  return result;
}

// The CBTL side of a Likert answer: the stored options say which option was CBTL's.
function cbtlPreference(likert, options) {
  const cbtlIndex = options.findIndex((o) => o.approach === 'cbtl');
  return cbtlIndex === 1 ? likert : 6 - likert;
}

function checkExport(cbtl, db, expected) {
  const result = run(cbtl, ['study', 'export', db, '--format', 'jsonl']);
  check(result.status === 0, `cbtl study export failed (status ${result.status}):\n${result.stderr}`);
  const records = result.stdout.split('\n').filter((line) => line.trim()).map((line, i) => {
    try {
      return JSON.parse(line);
    } catch (e) {
      return fail(`cbtl study export: line ${i + 1} is not JSON: ${line}`);
    }
  }).filter((r) => r.participant === PARTICIPANT).sort((x, y) => x.trial_index - y.trial_index);
  check(records.length === PAGES, `the export holds ${records.length} records of ${PARTICIPANT}, not ${PAGES}`);

  let lastElapsed = -1;
  records.forEach((record, i) => {
    const want = expected[i];
    const where = `exported record ${i}`;
    check(record.trial_index === i, `${where}: trial index ${record.trial_index}`);
    check(record.kind === want.kind, `${where}: kind ${record.kind}, expected ${want.kind}`);
    check(record.meal === want.meal, `${where}: meal ${record.meal}, expected ${want.meal}`);
    for (const [key, value] of Object.entries(want.response)) {
      check(isDeepStrictEqual(record.response[key], value),
        `${where} (${want.kind}): ${key} is ${JSON.stringify(record.response[key])}, the test answered ` +
        JSON.stringify(value));
    }
    if (want.kind === 'rating') {
      const options = record.response.options || [];
      check(options.length === 2 && options.some((o) => o.approach === 'cbtl'),
        `${where}: the stored options do not say which was CBTL's: ${JSON.stringify(options)}`);
      check(record.response.cbtl_preference === cbtlPreference(want.response.likert, options),
        `${where}: cbtl_preference ${record.response.cbtl_preference} does not match Likert ` +
        `${want.response.likert} with options ${options.map((o) => o.approach).join(' / ')}`);
    }
    check(Number.isInteger(record.elapsed_ms) && record.elapsed_ms >= lastElapsed,
      `${where}: elapsed_ms ${record.elapsed_ms} after ${lastElapsed}`);
    check(Number.isInteger(record.rt_ms) && record.rt_ms >= 0, `${where}: rt_ms ${record.rt_ms}`);
    lastElapsed = record.elapsed_ms;
  });
  log(`export: the ${PAGES} records of ${PARTICIPANT} hold what the test answered ` +
    `(elapsed ${records[0].elapsed_ms} .. ${lastElapsed} ms)`);
  return records;
}

// A CSV file of `cbtl study analyze --out` as objects by column name (its fields hold no commas or quotes).
function readCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  const header = lines[0].split(',');
  return lines.slice(1).map((line) => Object.fromEntries(line.split(',').map((cell, i) => [header[i], cell])));
}

// The analysis must say what was clicked: with one participant, each meal's mean preference is their answer, each
// prediction is right exactly when CBTL offered what they answered, and each question's path is their answers.
function checkAnalyze(cbtl, db, records, artifacts) {
  const dir = path.join(artifacts, 'analysis');
  const result = run(cbtl, ['study', 'analyze', db, '--out', dir, '--force']);
  console.log(result.stdout);
  if (result.stderr) console.log(result.stderr);
  check(result.status === 0, `cbtl study analyze failed (status ${result.status})`);
  check(/participants: 1 begun, 1 consented, 1 completed/.test(result.stdout),
    'cbtl study analyze does not report 1 completed participant');
  const ratings = readCsv(path.join(dir, 'ratings.csv'));
  const accuracy = readCsv(path.join(dir, 'accuracy.csv'));
  const paths = readCsv(path.join(dir, 'paths.csv'));
  const answers = records.filter((r) => r.kind === 'answers');
  for (const rating of records.filter((r) => r.kind === 'rating')) {
    const row = ratings.find((r) => Number(r.meal) === rating.meal);
    check(row && Number(row.n) === 1 && Number(row.mean) === rating.response.cbtl_preference,
      `ratings.csv meal ${rating.meal}: ${JSON.stringify(row)}, the clicked answer is ${rating.response.cbtl_preference}`);
  }
  for (const a of answers) {
    for (const q of ['dip', 'signal', 'verbosity']) {
      const row = accuracy.find((r) => Number(r.meal) === a.meal && r.measure === 'predicted' &&
        r.approach === 'cbtl' && r.question === q);
      const right = a.response.predicted.cbtl[q] === a.response[q] ? 1 : 0;
      check(row && Number(row.hits) === right && Number(row.total) === 1,
        `accuracy.csv meal ${a.meal} ${q}: ${JSON.stringify(row)}, CBTL offered ` +
        `${a.response.predicted.cbtl[q]} and the test answered ${a.response[q]}`);
    }
  }
  for (const q of ['dip', 'signal', 'verbosity']) {
    const clicked = answers.map((a) => a.response[q]).join(' > ');
    const row = paths.find((r) => r.question === q);
    check(row && row.path === clicked && Number(row.count) === 1,
      `paths.csv ${q}: ${JSON.stringify(row)}, the test answered ${clicked}`);
  }
  log('analysis: every meal\'s preference, every prediction and every path are what the test clicked');
}

// ---------------------------------------------------------------------------------------------------------------

function removeDatabase(db) {
  for (const suffix of ['', '-wal', '-shm', '-journal']) fs.rmSync(db + suffix, {force: true});
}

async function main() {
  const args = parseCommandLine();
  fs.mkdirSync(args.artifacts, {recursive: true});
  const db = path.join(args.artifacts, 'study.sqlite');
  removeDatabase(db);  // browser-1 must start as a new participant

  const server = new StudyServer(args.cbtl, args.program, db);
  let browser = null;
  let b = null;
  const stopAll = async () => {
    if (browser) await browser.close().catch(() => {});
    browser = null;
    await server.stop();
  };
  process.on('SIGINT', () => stopAll().then(() => process.exit(130)));
  // Whatever ends this process (an exception thrown inside a Playwright route handler escapes the try below),
  // the server must not outlive it.
  process.on('exit', () => {
    const child = server.child;
    if (child && child.exitCode === null && child.signalCode === null) child.kill('SIGTERM');
  });
  process.on('uncaughtException', (error) => {
    console.error(`[test] FAIL: ${error.stack || error}`);
    console.log('0 passed, 1 failed');
    process.exit(1);
  });

  try {
    const {url} = await server.start(0);
    browser = await chromium.launch({executablePath: '/usr/bin/chromium', args: CHROMIUM_ARGS});
    const context = await browser.newContext({viewport: VIEWPORT});
    context.setDefaultTimeout(60_000);
    b = new Browser(await context.newPage());
    b.origin = new URL(url).origin;
    const expected = [];
    await b.page.goto(`${url}p/${PARTICIPANT}`);
    await takeStudy(b, server, args.artifacts, expected);
    b.checkHealthy('the end');
    await browser.close();
    browser = null;
    await stopCleanly(server);

    const records = checkExport(args.cbtl, db, expected);
    checkAnalyze(args.cbtl, db, records, args.artifacts);
    check(laterFailures.length === 0, laterFailures.join('\n       '));
    log('PASS: the web study works in Chromium, end to end');
    console.log('1 passed, 0 failed');
    return 0;
  } catch (error) {
    if (b && browser) {
      await b.page.screenshot({path: path.join(args.artifacts, 'failure.png'), fullPage: true}).catch(() => {});
    }
    console.error(`[test] FAIL: ${error instanceof TestFailure ? error.message : error.stack}`);
    console.log('0 passed, 1 failed');
    return 1;
  } finally {
    await stopAll();
  }
}

process.exitCode = await main();
