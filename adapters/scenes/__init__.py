"""The built-in scenes, one module each, registered as ``lightrocks.scenes`` entry points."""
