"""The robots LightRocks ships, one module each, registered by ``lightrocks.robots``."""
