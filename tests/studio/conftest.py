"""The browser of the monitor's page tests, for the studio's page."""

from monitor.test_monitor_page import browser  # noqa: F401
