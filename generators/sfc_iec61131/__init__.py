"""LightRocks sfc_iec61131 package."""
