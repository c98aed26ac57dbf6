#!/usr/bin/python3
"""Real-browser test of netmc-server's lab console (docs/operations/console.md).

Drives headless Chromium (Debian's chromium and chromium-driver, python3-selenium) against a
running netmc-server --http with a token and two axis nodes:

  1. the page lists the expected nodes;
  2. a job started without the token is refused (401 shown, no job row);
  3. with the token the job starts, and the live contour's point count grows while it runs;
  4. a second job queues behind the first; its cancel without the token is refused (it stays
     queued), with the token it is cancelled;
  5. the first job ends done; the page's table of ended iterations (the exact numbers of its
     data-value attributes) is written to --results-json for the caller to compare;
  6. the browser's console holds no error or warning (the two provoked 401 answers aside).

Exit 0 on success; otherwise 1 with one line naming the failed step.

Usage: console_test.py --url http://127.0.0.1:PORT/ --token TOKEN --expect-nodes N1,N2
         [--insecure] --results-json FILE [--preset seed001] [--controller adrc+ilccc]
         [--iterations 3] [--clock realtime]
"""

import argparse
import json
import os
import sys
import time

try:
    from selenium import webdriver
    from selenium.common.exceptions import StaleElementReferenceException, WebDriverException
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select
except ImportError:
    # Debian's python3-selenium lives in the system interpreter; another python3 first on PATH
    # (a virtualenv, pyenv) does not see it.
    system_python = '/usr/bin/python3'
    if os.path.realpath(sys.executable) != os.path.realpath(system_python) and os.path.exists(system_python) \
            and not os.environ.get('NETMC_CONSOLE_TEST_REEXEC'):
        os.environ['NETMC_CONSOLE_TEST_REEXEC'] = '1'
        os.execv(system_python, [system_python] + sys.argv)
    print('console_test: FAILED at step "set-up": python3-selenium is not installed (apt-get install python3-selenium)',
          file=sys.stderr)
    sys.exit(1)

CHROMIUM = '/usr/bin/chromium'
CHROMEDRIVER = '/usr/bin/chromedriver'
POLL_S = 0.3


class StepFailed(Exception):
    pass


def log(text):
    print('console_test: ' + text, flush=True)


def wait_for(what, predicate, timeout_s, poll_s=POLL_S):
    """Polls predicate() until it returns something truthy; that value, or StepFailed(what)."""
    deadline = time.monotonic() + timeout_s
    last_error = None
    while True:
        try:
            value = predicate()
            if value:
                return value
        except StaleElementReferenceException as error:
            last_error = error
        if time.monotonic() >= deadline:
            detail = ' (last error: %s)' % last_error.__class__.__name__ if last_error else ''
            raise StepFailed('%s: not within %.0f s%s' % (what, timeout_s, detail))
        time.sleep(poll_s)


class Console:
    """The page, read through small scripts (robust against rows being updated in place)."""

    def __init__(self, driver):
        self.driver = driver

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def node_names(self):
        return self.js("return Array.from(document.querySelectorAll('#nodes tr.node'))"
                       ".map(r => r.getAttribute('data-node'));")

    def job_ids(self):
        return set(self.js("return Array.from(document.querySelectorAll('#jobs tr.job'))"
                           ".map(r => r.getAttribute('data-job'));"))

    def job_state(self, job):
        return self.js("const r = document.querySelector('#jobs tr.job[data-job=\"' + CSS.escape(arguments[0]) + '\"]');"
                       "return r ? r.getAttribute('data-state') : null;", job)

    def job_detail(self, job):
        return self.js("const r = document.querySelector('#jobs tr.job[data-job=\"' + CSS.escape(arguments[0]) + '\"]');"
                       "return r ? Array.from(r.cells).slice(0, 5).map(c => c.textContent.trim()).filter(t => t).join(' | ') : '';", job)

    def contour_points(self):
        value = self.js("return document.getElementById('contour').getAttribute('data-points');")
        return int(value) if value not in (None, '') else 0

    def message(self):
        """(#message's data-status, its text, its data-job)."""
        return tuple(self.js("const m = document.getElementById('message');"
                             "return [m.getAttribute('data-status') || '', m.textContent, m.getAttribute('data-job') || ''];"))

    def reset_message(self):
        self.js("const m = document.getElementById('message');"
                "m.setAttribute('data-status', ''); m.setAttribute('data-job', ''); m.textContent = '';")

    def answer(self, what, timeout_s=10):
        """Waits for the answer of the request just made: (status, text, job)."""
        def ready():
            status, text, job = self.message()
            return (status, text, job) if status not in ('', 'pending') else None
        return wait_for(what + ': no answer shown in #message', ready, timeout_s)

    def set_token(self, token):
        field = self.driver.find_element(By.ID, 'token')
        field.clear()
        if token:
            field.send_keys(token)
        # The page reads the field when it sends; make sure the field holds exactly this.
        if field.get_attribute('value') != token:
            raise StepFailed('token field: could not set it')

    def fill_form(self, args):
        Select(self.driver.find_element(By.ID, 'preset')).select_by_value(args.preset)
        controller = self.driver.find_element(By.ID, 'controller')
        controller.clear()
        controller.send_keys(args.controller)
        iterations = self.driver.find_element(By.ID, 'iteration-count')
        iterations.clear()
        iterations.send_keys(str(args.iterations))
        Select(self.driver.find_element(By.ID, 'clock')).select_by_value(args.clock)

    def click_start(self):
        self.reset_message()
        self.driver.find_element(By.ID, 'start').click()

    def click_in_job_row(self, job, selector):
        def click():
            rows = self.driver.find_elements(By.CSS_SELECTOR, '#jobs tr.job[data-job="%s"]' % job)
            if not rows:
                return False
            rows[0].find_element(By.CSS_SELECTOR, selector).click()
            return True
        wait_for('job %s: its row to click' % job, click, 10)

    def click_cancel(self, job):
        self.reset_message()
        self.click_in_job_row(job, 'button.cancel')

    def iteration_table(self):
        return self.js("""
            return Array.from(document.querySelectorAll('table#iterations tr.iteration')).map(r => {
              const v = c => { const e = r.querySelector('td.' + c); return e ? e.getAttribute('data-value') : null; };
              return {iteration: r.getAttribute('data-iteration'), e_max_m: v('e_max_m'), e_rms_m: v('e_rms_m'),
                      e_sum_m: v('e_sum_m'), deadline_misses: v('deadline_misses')};
            });""")

    def live_job(self):
        return self.js("return document.getElementById('live-job').getAttribute('data-job');")


def make_driver(args):
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ('--headless=new', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage',
                 '--window-size=1400,2200', '--no-first-run', '--no-default-browser-check',
                 '--disable-background-networking', '--disable-component-update', '--disable-default-apps',
                 '--disable-sync', '--disable-extensions', '--disable-domain-reliability',
                 '--disable-client-side-phishing-detection', '--no-proxy-server',
                 '--disable-features=Translate,OptimizationHints,MediaRouter,AutofillServerCommunication'):
        options.add_argument(flag)
    if args.insecure:
        options.add_argument('--ignore-certificate-errors')
        options.set_capability('acceptInsecureCerts', True)
    options.set_capability('goog:loggingPrefs', {'browser': 'ALL'})
    driver = webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=options)
    driver.set_page_load_timeout(30)
    driver.set_script_timeout(10)
    return driver


def is_provoked_refusal(entry):
    """The network errors Chromium logs for the two 401 answers this test provokes on purpose."""
    message = entry.get('message', '')
    return entry.get('source') == 'network' and entry.get('level') == 'SEVERE' and '/api/jobs' in message \
        and 'status of 401' in message


def run(args, driver, state):
    page = Console(driver)

    state['step'] = 'open the page'
    driver.get(args.url)
    try:
        wait_for('the page to load',
                 lambda: page.js("return document.getElementById('connection') !== null && "
                                 "typeof Dygraph === 'function';"), 20)
    except StepFailed:
        title = page.js('return document.title;')
        hint = '' if args.insecure or not args.url.startswith('https:') else \
            ' (a self-signed certificate needs --insecure)'
        raise StepFailed('the console page with dygraphs did not load within 20 s: the browser shows %r%s' % (
            title, hint))
    log('page open: ' + args.url)

    state['step'] = 'nodes listed'
    expected = [n for n in args.expect_nodes.split(',') if n]

    def nodes_listed():
        names = page.node_names()
        return all(n in names for n in expected)
    try:
        wait_for('nodes', nodes_listed, 20)
    except StepFailed:
        raise StepFailed('expected nodes %s, the page lists %s (connection: %s)' % (
            ','.join(expected), ','.join(page.node_names()) or 'none',
            page.js("return document.getElementById('connection').textContent.replace(/\\s+/g, ' ').trim();")))
    log('nodes listed: ' + ', '.join(expected))

    state['step'] = 'presets loaded'
    wait_for('preset %s in #preset' % args.preset,
             lambda: args.preset in page.js("return Array.from(document.querySelectorAll('#preset option'))"
                                            ".map(o => o.value);"), 15)

    state['step'] = 'start without the token is refused'
    before = page.job_ids()
    page.set_token('')
    page.fill_form(args)
    page.click_start()
    status, text, _ = page.answer('start without token', 20)
    if status != '401':
        raise StepFailed('expected a 401 refusal in #message, got status %r: %s' % (status, text))
    if '401' not in text:
        raise StepFailed('#message does not show the 401: %r' % text)
    time.sleep(1.5)  # three state messages
    appeared = page.job_ids() - before
    if appeared:
        raise StepFailed('a job row appeared although the start was refused: %s' % ', '.join(sorted(appeared)))
    log('start without token refused: ' + text)

    state['step'] = 'start with the token'
    page.set_token(args.token)
    page.click_start()
    status, text, job = page.answer('start with token', 20)
    if status != '202' or not job:
        raise StepFailed('expected 202 and a job id in #message, got status %r: %s' % (status, text))
    state['job'] = job
    wait_for('job %s: its row' % job, lambda: job in page.job_ids(), 10)
    log('job %s started: %s' % (job, text))

    state['step'] = 'job %s runs' % job

    def running():
        s = page.job_state(job)
        if s in ('done', 'failed', 'cancelled'):
            raise StepFailed('job %s ended (%s) before it was seen running: %s' % (job, s, page.job_detail(job)))
        return s == 'running'
    wait_for('job %s to run' % job, running, 60)
    page.click_in_job_row(job, 'td.id')  # show this job in the live section

    state['step'] = 'live contour grows'
    readings = []
    increases = 0
    deadline = time.monotonic() + 30
    while increases < 2:
        points = page.contour_points()
        if readings and points > readings[-1]:
            increases += 1
        readings.append(points)
        if increases >= 2:
            break
        s = page.job_state(job)
        if s != 'running':
            raise StepFailed('job %s left running (%s) before the contour grew twice: readings %s' % (
                job, s, readings[-10:]))
        if time.monotonic() > deadline:
            raise StepFailed('contour data-points did not grow twice within 30 s: readings %s' % readings[-10:])
        time.sleep(POLL_S)
    log('contour grows: data-points %s' % ' -> '.join(str(r) for r in sorted(set(readings))[-3:]))

    state['step'] = 'second job queues'
    page.fill_form(args)
    page.click_start()
    status, text, second = page.answer('start of the second job', 20)
    if status != '202' or not second:
        raise StepFailed('expected 202 for the second job, got status %r: %s' % (status, text))
    state['second'] = second
    wait_for('job %s: its row' % second, lambda: second in page.job_ids(), 10)
    time.sleep(0.6)
    s = page.job_state(second)
    if s != 'queued':
        raise StepFailed('job %s should queue behind job %s (same axes) but is %s: %s' % (
            second, job, s, page.job_detail(second)))
    log('job %s queued: %s' % (second, page.job_detail(second)))

    state['step'] = 'cancel without the token is refused'
    page.set_token('')
    page.click_cancel(second)
    status, text, _ = page.answer('cancel without token')
    if status != '401' or '401' not in text:
        raise StepFailed('expected a 401 refusal in #message, got status %r: %s' % (status, text))
    time.sleep(1.5)
    s = page.job_state(second)
    if s != 'queued':
        raise StepFailed('job %s should still be queued after the refused cancel, is %s' % (second, s))
    log('cancel without token refused: ' + text)

    state['step'] = 'cancel with the token'
    page.set_token(args.token)
    page.click_cancel(second)
    status, text, _ = page.answer('cancel with token')
    if status != '200':
        raise StepFailed('expected 200 for the cancel, got status %r: %s' % (status, text))
    # A cancelled queued job leaves the queue at once (the next state message shows it).
    wait_for('job %s: data-state cancelled' % second, lambda: page.job_state(second) == 'cancelled', 5)
    log('job %s cancelled while queued' % second)

    state['step'] = 'job %s done' % job

    def done():
        s = page.job_state(job)
        if s in ('failed', 'cancelled'):
            raise StepFailed('job %s ended %s: %s' % (job, s, page.job_detail(job)))
        return s == 'done'
    wait_for('job %s: data-state done' % job, done, 90 + 30 * args.iterations, poll_s=0.5)
    log('job %s done' % job)

    # A finished job counts every iteration it ran, before and after a reload.
    expected = '%d / %d' % (args.iterations, args.iterations)

    def progress():
        return page.js("const r = document.querySelector('#jobs tr.job[data-job=\"' + CSS.escape(arguments[0]) + '\"]');"
                       "return r ? r.cells[3].textContent.trim() : '';", job)
    wait_for('job %s: progress %s' % (job, expected), lambda: progress() == expected, 5)
    driver.refresh()
    wait_for('job %s after a reload: progress %s' % (job, expected), lambda: progress() == expected, 15)
    legend = page.js("const l = document.getElementById('learning-legend'); return l ? l.textContent : '';")
    if 'e_max' not in legend or 'e_sum' not in legend:
        raise StepFailed('the learning curve has no legend naming e_max and e_sum: %r' % legend)
    log('job %s shows %s, after a reload too; learning curve legend: %s' % (job, expected, ' '.join(legend.split())))

    state['step'] = 'iteration table'
    if page.live_job() != job:
        page.click_in_job_row(job, 'td.id')
    wait_for('live section to show job %s' % job, lambda: page.live_job() == job, 10)

    def table_complete():
        rows = page.iteration_table()
        return rows if len(rows) == args.iterations else None
    try:
        rows = wait_for('iteration table', table_complete, 15)
    except StepFailed:
        raise StepFailed('the iteration table shows %d rows, expected %d' % (len(page.iteration_table()),
                                                                            args.iterations))
    iterations = []
    for row in rows:
        try:
            iterations.append({
                'iteration': int(row['iteration']),
                'e_max_m': float(row['e_max_m']),
                'e_rms_m': float(row['e_rms_m']),
                'e_sum_m': float(row['e_sum_m']),
                'deadline_misses': int(float(row['deadline_misses'])),
            })
        except (TypeError, ValueError):
            raise StepFailed('iteration row with a missing or unreadable data-value: %r' % row)
    numbers = [it['iteration'] for it in iterations]
    if numbers != list(range(1, args.iterations + 1)):
        raise StepFailed('iteration numbers %s, expected 1..%d' % (numbers, args.iterations))
    results = {'job': int(job) if job.isdigit() else job, 'iterations': iterations}
    with open(args.results_json, 'w') as out:
        json.dump(results, out, indent=2)
        out.write('\n')
    log('iteration table of job %s written to %s: %s' % (job, args.results_json, ', '.join(
        'e_max %.3f um' % (it['e_max_m'] * 1e6) for it in iterations)))

    state['step'] = 'browser console'
    entries = driver.get_log('browser')
    provoked = [e for e in entries if is_provoked_refusal(e)]
    bad = [e for e in entries if e.get('level') in ('SEVERE', 'WARNING') and not is_provoked_refusal(e)]
    if bad:
        first = bad[0]
        raise StepFailed('%d console error(s)/warning(s), first: [%s] %s' % (
            len(bad), first.get('level'), first.get('message', '').replace('\n', ' ')[:300]))
    if len(provoked) > 2:
        raise StepFailed('%d refused requests logged, only 2 were provoked' % len(provoked))
    log('browser console clean (%d entries, %d of them the provoked 401s)' % (len(entries), len(provoked)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--url', required=True, help='the console, e.g. http://127.0.0.1:PORT/')
    parser.add_argument('--token', required=True, help="the server's token")
    parser.add_argument('--expect-nodes', required=True, help='axis nodes the page must list, comma-separated')
    parser.add_argument('--insecure', action='store_true', help='accept a self-signed certificate')
    parser.add_argument('--results-json', required=True, help="where to write the page's iteration table")
    parser.add_argument('--preset', default='seed001')
    parser.add_argument('--controller', default='adrc+ilccc')
    parser.add_argument('--iterations', type=int, default=3)
    parser.add_argument('--clock', default='realtime', choices=['realtime', 'lockstep'])
    args = parser.parse_args()
    if args.iterations < 1:
        parser.error('--iterations: at least 1')

    state = {'step': 'start the browser'}
    driver = None
    try:
        driver = make_driver(args)
        run(args, driver, state)
    except StepFailed as error:
        print('console_test: FAILED at step "%s": %s' % (state['step'], error), file=sys.stderr)
        return 1
    except WebDriverException as error:
        detail = (error.msg or str(error)).strip().splitlines()
        print('console_test: FAILED at step "%s": browser: %s' % (state['step'], detail[0] if detail else error),
              file=sys.stderr)
        return 1
    except Exception as error:  # noqa: BLE001 - one clear line for any failure
        print('console_test: FAILED at step "%s": %s: %s' % (state['step'], error.__class__.__name__, error),
              file=sys.stderr)
        return 1
    finally:
        if driver is not None:
            try:
                driver.quit()
            except Exception:  # noqa: BLE001
                pass
    log('PASSED')
    return 0


if __name__ == '__main__':
    sys.exit(main())
