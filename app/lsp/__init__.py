"""The LightRocks language server: the workbench's checks and printers behind LSP."""
