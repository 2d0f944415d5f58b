#!/usr/bin/python3
"""Opens a golden report folder's report.html (src/golden/report_html.hpp) in headless Chromium, as a
person would when CI fails, and checks what they would see:

with JavaScript on
  - every <img> has loaded (naturalWidth > 0): the pictures beside the report are found through
    their relative, percent-encoded paths;
  - the slider: moving its range changes the overlay's clip-path; the blink comparison: a click on
    its picture switches expected and actual, and its button makes them alternate;
  - the browser's console holds no error (a missing file, a script error, a favicon request);
with JavaScript off (Chrome's content setting)
  - the failure sections, their numbers, commands and expected, actual and diff pictures are
    there and loaded, and the interactive widgets are hidden (the page is whole without them).

Debian's chromium, chromium-driver and python3-selenium (scripts/deps test). Run by CTest's
golden-report:browser on the sample report that golden-report:sample writes
(tests/test_golden_report.cpp).

usage: browser_test.py REPORT_FOLDER [--screenshot FILE.png]
Exit 0 when every check passes, 1 with one line per failed check, 2 when it cannot run.
"""
import argparse
import os
import pathlib
import shutil
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree, whoever runs this
from checklist import check, finish  # noqa: E402  (after the line above)

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
PAGE_LOAD_SECONDS = 60
WAIT_SECONDS = 30


def wait_for(predicate, seconds=WAIT_SECONDS, interval=0.1):
    """predicate()'s first true value within `seconds`, else its last value."""
    deadline = time.monotonic() + seconds
    while True:
        value = predicate()
        if value or time.monotonic() > deadline:
            return value
        time.sleep(interval)


def start_browser(webdriver, profile, javascript):
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    options.add_argument("--headless=new")
    if os.geteuid() == 0:
        options.add_argument("--no-sandbox")  # Chromium's sandbox refuses to run as root
    options.add_argument("--disable-dev-shm-usage")  # containers with a small /dev/shm
    options.add_argument(f"--user-data-dir={profile}")
    options.add_argument("--window-size=1280,2400")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    if not javascript:
        options.add_experimental_option("prefs", {"profile.managed_default_content_settings.javascript": 2})
    service = webdriver.ChromeService(executable_path=CHROMEDRIVER) if hasattr(webdriver, "ChromeService") else None
    if service is None:
        from selenium.webdriver.chrome.service import Service

        service = Service(executable_path=CHROMEDRIVER)
    driver = webdriver.Chrome(service=service, options=options)
    driver.set_page_load_timeout(PAGE_LOAD_SECONDS)
    driver.set_script_timeout(WAIT_SECONDS)
    return driver


def images_state(driver):
    """[(src, complete, naturalWidth)] of every <img>, read through the WebDriver protocol."""
    from selenium.webdriver.common.by import By

    return [
        (img.get_attribute("src"), img.get_property("complete"), img.get_property("naturalWidth") or 0)
        for img in driver.find_elements(By.TAG_NAME, "img")
    ]


def check_images_loaded(driver, which):
    state = wait_for(lambda: (s := images_state(driver)) and all(c for _, c, _ in s) and s, interval=0.2)
    state = state or images_state(driver)
    check(len(state) > 0, f"{which}: the page has pictures ({len(state)})")
    broken = [src for src, complete, width in state if not complete or width <= 0]
    check(not broken, f"{which}: every picture loaded" + (f"; not: {', '.join(broken)}" if broken else ""))


def check_console(driver, which):
    severe = [entry for entry in driver.get_log("browser") if entry.get("level") == "SEVERE"]
    for entry in severe:
        print(f"  console: {entry.get('message')}")
    check(not severe, f"{which}: no errors in the browser's console")


def check_with_javascript(webdriver, url, profile, screenshot):
    from selenium.webdriver.common.by import By

    driver = start_browser(webdriver, profile, javascript=True)
    try:
        driver.get(url)
        check("golden" in driver.title, f"JavaScript on: the page's title names the check ({driver.title!r})")
        check_images_loaded(driver, "JavaScript on")
        widgets = driver.find_elements(By.CSS_SELECTOR, ".compare")
        if not check(len(widgets) > 0, "JavaScript on: the report has a slider and blink comparison"):
            return
        widget = widgets[0]
        driver.execute_script("arguments[0].scrollIntoView()", widget)
        check(widget.is_displayed(), "JavaScript on: the comparison is shown once the script has run")

        over = widget.find_element(By.CSS_SELECTOR, ".slider img.over")
        slider = widget.find_element(By.CSS_SELECTOR, ".slider input[type=range]")
        clip = "return getComputedStyle(arguments[0]).clipPath"
        before = driver.execute_script(clip, over)
        driver.execute_script(
            "arguments[0].value = 20; arguments[0].dispatchEvent(new Event('input', {bubbles: true}))", slider
        )
        after = driver.execute_script(clip, over)
        check(before != after and "80%" in after, f"JavaScript on: the slider moves the cut ({before} → {after})")

        picture = widget.find_element(By.CSS_SELECTOR, ".blink img")
        expected, actual = widget.get_attribute("data-expected"), widget.get_attribute("data-actual")
        before = picture.get_attribute("src")
        picture.click()
        after = picture.get_attribute("src")
        check(
            before.endswith(expected) and after.endswith(actual),
            f"JavaScript on: a click on the blink picture switches expected to actual ({before} → {after})",
        )
        button = widget.find_element(By.CSS_SELECTOR, ".blink button")
        button.click()
        seen = set()
        wait_for(lambda: seen.add(picture.get_attribute("src")) or len(seen) >= 2, seconds=5, interval=0.05)
        check(len(seen) >= 2, f"JavaScript on: the blink button alternates the pictures ({len(seen)} seen in 5 s)")
        check(button.get_attribute("aria-pressed") == "true", "JavaScript on: the blink button says it is on")
        button.click()
        check(button.get_attribute("aria-pressed") == "false", "JavaScript on: a second click stops the blinking")
        if screenshot:
            driver.execute_script("window.scrollTo(0, 0)")
            driver.save_screenshot(screenshot)
            print(f"screenshot: {screenshot}")
        check_console(driver, "JavaScript on")
    finally:
        driver.quit()


def check_without_javascript(webdriver, url, profile):
    from selenium.webdriver.common.by import By

    driver = start_browser(webdriver, profile, javascript=False)
    try:
        driver.get(url)
        sections = driver.find_elements(By.CSS_SELECTOR, "section.result")
        check(len(sections) > 0 and all(s.is_displayed() for s in sections),
              f"JavaScript off: the failure sections are shown ({len(sections)})")
        check_images_loaded(driver, "JavaScript off")
        pictures = driver.find_elements(By.CSS_SELECTOR, "section.result .pictures img")
        alts = " ".join(p.get_attribute("alt") for p in pictures if p.is_displayed())
        check(all(f"{kind} frame" in alts for kind in ("expected", "actual", "diff")),
              "JavaScript off: expected, actual and diff pictures are shown side by side")
        commands = driver.find_elements(By.CSS_SELECTOR, "section.result pre code")
        check(any(c.is_displayed() and c.text.strip() for c in commands),
              "JavaScript off: the commands that reproduce a failure are shown")
        widgets = driver.find_elements(By.CSS_SELECTOR, ".compare")
        check(len(widgets) > 0 and all(w.get_attribute("hidden") is not None for w in widgets),
              "JavaScript off: the page's script did not run (the widgets keep their hidden attribute)")
        check(not any(w.is_displayed() for w in widgets), "JavaScript off: the slider and blink widgets are not shown")
        controls = driver.find_elements(By.CSS_SELECTOR, ".compare input, .compare button")
        check(not any(c.is_displayed() for c in controls), "JavaScript off: no dead slider or button is shown")
        check_console(driver, "JavaScript off")
    finally:
        driver.quit()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--screenshot", help="save the page (JavaScript on) as this PNG")
    args = parser.parse_args()
    report = pathlib.Path(args.folder).resolve() / "report.html"
    if not report.is_file():
        print(f"browser_test: no {report}: run CTest's golden-report:sample first", file=sys.stderr)
        return 2
    try:
        from selenium import webdriver
    except ImportError as e:
        print(f"browser_test: cannot import selenium ({e}): install python3-selenium (scripts/deps test)",
              file=sys.stderr)
        return 2
    for program in (CHROMIUM, CHROMEDRIVER):
        if not os.access(program, os.X_OK):
            print(f"browser_test: no {program}: install chromium and chromium-driver (scripts/deps test)",
                  file=sys.stderr)
            return 2
    url = report.as_uri()
    profile = tempfile.mkdtemp(prefix="particles-browser-test-")
    try:
        check_with_javascript(webdriver, url, os.path.join(profile, "on"), args.screenshot)
        check_without_javascript(webdriver, url, os.path.join(profile, "off"))
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    return finish("browser_test", url)


if __name__ == "__main__":
    sys.exit(main())
