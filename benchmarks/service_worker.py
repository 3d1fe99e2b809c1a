"""Worker: a Trigger service to call, as a Skydeck node or as a bare FastAPI endpoint.

    python -m benchmarks.service_worker skydeck    # a node serving /bench/trigger; READY {"url"}
    python -m benchmarks.service_worker fastapi    # the same path on a bare FastAPI app

Both run uvicorn on the standard asyncio event loop (a node runs its server in its own loop,
which ``spin`` starts with ``asyncio.run``), so the comparison is the framework, not the loop.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib

import uvicorn
from fastapi import FastAPI

from benchmarks.processes import free_port
from benchmarks.sink import emit, wait_for_stop_async
from services.runtime import Node, NodeSettings
from services.runtime.executor import run
from shared_models.std_srvs import Trigger, TriggerResponse

SERVICE = "/bench/trigger"


async def skydeck() -> None:
    node = Node("bench_trigger", settings=NodeSettings(port=0))
    node.create_service(Trigger, SERVICE, lambda request: TriggerResponse(success=True, message="ok"))
    await node.start()
    try:
        async with asyncio.timeout(20.0):
            await node._session.registered.wait()  # type: ignore[union-attr]
        emit("READY", {"url": node.url})
        await wait_for_stop_async()
    finally:
        await node.stop()


async def bare_fastapi() -> None:
    app = FastAPI()

    @app.post(SERVICE)
    async def trigger() -> dict[str, object]:
        return {"success": True, "message": "ok"}

    port = free_port()
    server = uvicorn.Server(
        uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning", access_log=False, lifespan="off")
    )
    server.capture_signals = contextlib.nullcontext  # type: ignore[method-assign,assignment]
    task = asyncio.create_task(server.serve())
    while not server.started:
        await asyncio.sleep(0.01)
    emit("READY", {"url": f"http://127.0.0.1:{port}"})
    await wait_for_stop_async()
    server.should_exit = True
    await task


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kind", choices=["skydeck", "fastapi"])
    args = parser.parse_args()
    run(skydeck() if args.kind == "skydeck" else bare_fastapi())


if __name__ == "__main__":
    main()
