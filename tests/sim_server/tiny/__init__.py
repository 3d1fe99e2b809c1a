"""A tiny third world, built in the tests from the floor alone: balls dropped on a ground.

It proves the house: a world is one package (this one: its world, settings, description and
node) plus one row in the table of worlds (``tests/sim_server/test_worlds.py`` adds it)."""
