#!/usr/bin/python3
"""The console's Axes table in headless Chromium against one emulated Modbus axis (node NODE,
axis AXIS, standing at 55 mm): enable refused without the token, then with it: enable, move to
65 mm and back to 55 mm (each read back within 1 um on the page), a jog while the button is held,
a quick stop. Prints the positions it saw as one JSON line for the calling script.

Usage: console_commissioning.py --url URL --token TOKEN --node NODE --axis AXIS
"""

import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from console_test import Console, StepFailed, log, make_driver, wait_for  # noqa: E402

from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402


class Axes(Console):
    def __init__(self, driver, node, axis):
        super().__init__(driver)
        self.selector = '#axes tr.axis[data-node="%s"][data-axis="%s"]' % (node, axis)

    def row(self):
        rows = self.driver.find_elements(By.CSS_SELECTOR, self.selector)
        return rows[0] if rows else None

    def cell(self, cls):
        return self.js("const r = document.querySelector(arguments[0]);"
                       "return r ? r.querySelector('td.' + arguments[1]).textContent : null;", self.selector, cls)

    def position_mm(self):
        return float(self.cell('position'))

    def click(self, action):
        self.reset_message()
        self.row().find_element(By.CSS_SELECTOR, 'button[data-action="%s"]' % action).click()

    def move_to(self, mm):
        field = self.row().find_element(By.CSS_SELECTOR, 'input.move-target')
        field.clear()
        field.send_keys(str(mm))
        self.click('move')

    def wait_holding_at(self, mm, timeout_s):
        def there():
            return self.cell('motion') == 'holding' and abs(self.position_mm() - mm) <= 0.001
        wait_for('axis holding at %.3f mm (it shows %s at %s mm)' % (mm, self.cell('motion'), self.cell('position')),
                 there, timeout_s)


def run(args, driver):
    page = Axes(driver, args.node, args.axis)
    driver.get(args.url)
    wait_for('the Axes table to list %s %s' % (args.node, args.axis), page.row, 20)
    log('axis listed: %s %s, %s, %s mm' % (args.node, args.axis, page.cell('state'), page.cell('position')))
    seen = {'start_mm': page.position_mm()}

    page.set_token('')
    page.click('enable')
    status, text, _ = page.answer('enable without the token')
    if status != '401':
        raise StepFailed('enable without the token: expected 401, the page shows %s: %s' % (status, text))
    time.sleep(1.0)  # a node status later: still off
    if page.cell('motion') != 'off' or page.cell('state') == 'Operation enabled':
        raise StepFailed('enable without the token moved the axis: %s, %s' % (page.cell('motion'), page.cell('state')))
    log('enable without the token refused: ' + text)

    page.set_token(args.token)
    page.click('enable')
    status, text, _ = page.answer('enable with the token')
    if status != '200':
        raise StepFailed('enable with the token: %s: %s' % (status, text))
    wait_for('the axis to hold', lambda: page.cell('motion') == 'holding', 10)
    log('enabled: %s, holding at %s mm' % (page.cell('state'), page.cell('position')))

    page.move_to(65)
    page.wait_holding_at(65.0, 15)
    seen['moved_mm'] = page.position_mm()
    page.move_to(55)
    page.wait_holding_at(55.0, 15)
    seen['back_mm'] = page.position_mm()
    log('moved to %.3f mm and back to %.3f mm' % (seen['moved_mm'], seen['back_mm']))

    button = page.row().find_element(By.CSS_SELECTOR, 'button[data-action="jog-plus"]')
    jogging = []
    actions = ActionChains(driver)
    actions.click_and_hold(button).perform()
    try:
        for _ in range(10):
            time.sleep(0.1)
            jogging.append(page.cell('motion'))
    finally:
        ActionChains(driver).release(button).perform()
    if 'jogging' not in jogging:
        raise StepFailed('holding the jog button did not jog the axis (motion seen: %s)' % ', '.join(jogging))
    wait_for('the axis to hold after the jog', lambda: page.cell('motion') == 'holding', 10)
    seen['jogged_mm'] = page.position_mm()
    log('jogged +: %.3f mm' % seen['jogged_mm'])

    page.click('quick-stop')
    wait_for('the quick stop', lambda: page.cell('motion') == 'off' and page.cell('state') != 'Operation enabled', 10)
    seen['stopped_state'] = page.cell('state')
    seen['stopped_mm'] = page.position_mm()
    log('quick stop: %s at %.3f mm' % (seen['stopped_state'], seen['stopped_mm']))
    return seen


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--url', required=True)
    parser.add_argument('--token', required=True)
    parser.add_argument('--node', required=True)
    parser.add_argument('--axis', required=True)
    parser.add_argument('--insecure', action='store_true')
    args = parser.parse_args()
    driver = make_driver(args)
    try:
        seen = run(args, driver)
    except (StepFailed, Exception) as error:  # noqa: B014 - every failure is reported the same way
        print('console_commissioning: FAILED: %s' % error, file=sys.stderr)
        return 1
    finally:
        driver.quit()
    print(json.dumps(seen))
    return 0


if __name__ == '__main__':
    sys.exit(main())
