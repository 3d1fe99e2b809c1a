"""Tests for the launch supervisor and launch files."""
