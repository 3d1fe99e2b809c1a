"""Skydeck services: the node runtime, the core, the CLI and the workshop nodes."""
