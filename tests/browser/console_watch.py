#!/usr/bin/python3
"""Keeps the console open in headless Chromium while a job runs elsewhere (console_browser.sh's
miss-rate comparison): opens --url, touches --ready once the page is connected and the browser
has settled, follows the live job until --stop appears (or --seconds pass), then writes the most
points its contour plot held to --points and fails on any browser console error."""
import argparse
import os
import sys
import time

from console_test import Console, make_driver


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--url', required=True)
    parser.add_argument('--seconds', type=float, default=60)
    parser.add_argument('--ready', required=True)
    parser.add_argument('--stop', required=True)
    parser.add_argument('--points', required=True)
    parser.add_argument('--insecure', action='store_true')
    parser.add_argument('--settle', type=float, default=2, help='seconds between the page listing the nodes and --ready')
    args = parser.parse_args()
    driver = make_driver(args)
    try:
        driver.get(args.url)
        page = Console(driver)
        deadline = time.time() + 20
        while len(page.node_names()) < 2:
            if time.time() > deadline:
                print('the page did not list the nodes')
                return 1
            time.sleep(0.2)
        # The browser's own start-up (its processes loading, the page's scripts compiling) over:
        # what is compared is a console left open, not a browser starting.
        time.sleep(args.settle)
        open(args.ready, 'w').close()
        most = 0
        end = time.time() + args.seconds
        while not os.path.exists(args.stop) and time.time() < end:
            most = max(most, page.contour_points())
            time.sleep(0.3)
        most = max(most, page.contour_points())
        with open(args.points, 'w') as out:
            out.write(f'{most}\n')
        errors = [e for e in driver.get_log('browser') if e.get('level') in ('SEVERE', 'WARNING')]
        if errors:
            print('browser console:', errors)
            return 1
        return 0
    finally:
        driver.quit()


if __name__ == '__main__':
    sys.exit(main())
