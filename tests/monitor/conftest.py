"""The browser fixtures of the monitor's page tests (see ``monitor.browser_page``)."""

from monitor.browser_page import browser, launch  # noqa: F401
