"""Adapters that speak other systems' protocols at Skydeck's one topic edge and service path."""
