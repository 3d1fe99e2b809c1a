"""Skydeck's simulator: a floor every world stands on, and one package per world.

The floor (this folder): a PyBullet client and its clock (``bullet``), poses (``geometry``),
input checks (``checks``: :class:`InvalidCommand`, the one exception for bad pilot or driver
input), the camera and its topics (``camera``, ``camera_stream``), every world's settings
(``settings``), what a world tells its clients (``description``) and the world node with the
one paced physics loop (``world_node``). The worlds: ``sim_server.drone`` (the workshop's drone
and boxes) and ``sim_server.robot`` (the Neato room), listed in one table (``worlds``) that
``skydeck run sim`` (``node``), the core's ``/api/config``, the CLI and the launcher read.

The floor never imports a world; a world imports only the floor (and the SDK and messages).
"""

from __future__ import annotations

from sim_server.checks import InvalidCommand

__all__ = ["InvalidCommand"]
