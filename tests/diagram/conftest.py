"""The browser and the monitor's launcher of the monitor's page tests, for the pages here."""

from monitor.browser_page import browser, launch  # noqa: F401
