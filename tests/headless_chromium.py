"""A real headless Chromium driven by Selenium, for tests that open a saved page (no tests
here).

Debian's `chromium` and its matching `chromium-driver` (`tests/run` installs both when
missing); Selenium only drives them through the WebDriver protocol, with the driver given by
path so that Selenium Manager never downloads anything. The browser runs offline: a proxy on
a closed port makes any network request fail, so a page that needed a CDN would break.
"""

import contextlib
import shutil
import tempfile

from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import WebDriverWait

# Flags that run Chromium headless as root in a container, with no background traffic.
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync",
                  "--enable-unsafe-swiftshader",  # WebGL in software, without a GPU
                  "--proxy-server=http://127.0.0.1:9", "--proxy-bypass-list=<-loopback>")
# Hang guards, not performance criteria: on a busy 2-core host the 6 MB replay takes minutes to
# parse, during which each WebDriver command waits for the page's main thread.
COMMAND_TIMEOUT_S = 900.0
INSTALL_HINT = ("install Debian's chromium and chromium-driver (apt-get install chromium "
                "chromium-driver; tests/run does)")


def missing_browser() -> str | None:
    """What is missing to run the browser, or None."""
    missing = [name for name in ("chromium", "chromedriver") if shutil.which(name) is None]
    return f"{' and '.join(missing)} not found: {INSTALL_HINT}" if missing else None


@contextlib.contextmanager
def headless_chromium(*, width: int = 1280, height: int = 800):
    """A WebDriver of a fresh headless Chromium (new empty profile), quit on exit."""
    problem = missing_browser()
    if problem:
        raise RuntimeError(problem)
    with tempfile.TemporaryDirectory(prefix="chromium-profile-") as profile:
        options = Options()
        options.binary_location = shutil.which("chromium")
        for flag in CHROMIUM_FLAGS:
            options.add_argument(flag)
        options.add_argument(f"--user-data-dir={profile}")
        options.add_argument(f"--window-size={width},{height}")
        options.page_load_strategy = "none"  # get() returns at once; tests wait for what they need
        driver = webdriver.Chrome(
            options=options, service=Service(executable_path=shutil.which("chromedriver")))
        driver.command_executor.client_config.timeout = COMMAND_TIMEOUT_S
        driver.set_script_timeout(COMMAND_TIMEOUT_S)
        try:
            yield driver
        finally:
            driver.quit()


def wait_until(driver, script: str, timeout_s: float = COMMAND_TIMEOUT_S):
    """Runs `script` (JavaScript returning a value) until it returns a truthy value."""
    return WebDriverWait(driver, timeout_s).until(lambda d: d.execute_script(script))
