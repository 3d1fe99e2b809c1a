"""Tests for the AI node and its tour planner."""
