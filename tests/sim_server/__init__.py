"""Tests of the simulator core (sim_server)."""
