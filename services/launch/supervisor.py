"""The supervisor behind ``skydeck launch`` (roslaunch): start, watch, respawn and stop nodes.

    spec = load_launch_file(default_launch_file())
    exit_code = asyncio.run(Supervisor(spec, LaunchOptions(base_port=9000)).run())

Every node starts at once, the core with them, as roslaunch starts its nodes (each waits for what
it needs: the core, a service, a topic; a node waits for a core starting beside it without
saying so); the launch is up when each answers ``GET /health`` with 200, and their ready lines
come in launch order. A launch with ROS 1 parameters (a roslaunch file's ``<param>``) starts its
core first and sets them on the core's parameter server before the other nodes start. Every child runs in its own session (its own
process group), so stopping a node kills whatever it started too, and a Ctrl-C in the terminal
reaches only the supervisor, which then stops the nodes in reverse order: SIGTERM to the group,
up to ``stop_timeout_s`` to exit, then SIGKILL. Children's output lines are forwarded with a
``[name]`` prefix; the supervisor's own lines start with ``[launch]``. A launch may carry ROS 1
parameters (a roslaunch file's ``<param>``): they are set on the core's parameter server once
the core answers, before any other node starts.
"""

from __future__ import annotations

import asyncio
import contextlib
import signal
import time
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, TextIO

from services.launch.child_process import Health, describe_exit, signal_group, spawn
from services.launch.errors import LaunchError
from services.launch.launched import (
    BACKOFF_FIRST_S,
    BACKOFF_MAX_S,
    BACKOFF_RESET_AFTER_S,
    LaunchedNode,
    NodeState,
    NodeStatus,
)
from services.launch.next_steps import next_steps
from services.launch.output import say, write_line
from services.launch.plan import (
    LaunchOptions,
    NodePlan,
    check_ports_free,
    default_command,
    plan_launch,
)
from services.launch.plan import core_url as launch_core_url
from services.launch.settings import LaunchSettings
from services.launch.spec import LaunchSpec
from services.runtime.http_client import HttpClient
from services.runtime.rosparam import RosParamClient, RosParamError

if TYPE_CHECKING:
    from services.runtime.node import Node
    from shared_models.skydeck_launch import KillNodeResponse

__all__ = ["CommandFor", "Supervisor"]

CommandFor = Callable[[NodePlan], Sequence[str]]
"""Turns a node's plan into the argv that starts it (``default_command`` runs the skydeck CLI)."""

# -- stopping -----------------------------------------------------------------------------------
STOP_TIMEOUT_S = 5.0


class Supervisor:
    """Starts a launch's nodes, respawns the ones that die and stops them all on request.

    ``command_for`` builds each node's argv (tests substitute small programs); ``out`` receives
    every line (default: standard output); ``control`` starts the launch's own node once the
    core is up (``/skydeck_launch``, which ``skydeck node kill`` asks); ``parameters`` (absolute
    name -> value, in order) go to the core's ROS 1 parameter server before the first node
    other than the core starts; ``settings`` are the launcher's (its environment, endpoint
    ports given there; read now if not given); ``core_url`` is a running core the launch uses
    (default: its own core's URL). Raises ``LaunchError`` at once for bad options.
    """

    def __init__(
        self,
        spec: LaunchSpec,
        options: LaunchOptions | None = None,
        *,
        command_for: CommandFor = default_command,
        out: TextIO | None = None,
        stop_timeout_s: float = STOP_TIMEOUT_S,
        control: bool = False,
        parameters: Sequence[tuple[str, object]] = (),
        settings: LaunchSettings | None = None,
        core_url: str | None = None,
    ) -> None:
        self._settings = settings or LaunchSettings()
        given = options or LaunchOptions()
        self.options = given.with_seed().with_given_ports(self._settings.endpoint_ports())
        self.plans = plan_launch(spec, self.options)
        self.core_url = core_url or launch_core_url(spec, self.options)
        self._show_seed = given.seed is None and any(
            "{seed}" in text for node in spec.nodes for text in (*node.args, *node.env.values())
        )
        self._command_for = command_for
        self._out = out
        self._stop_timeout_s = stop_timeout_s
        self._children = {plan.name: LaunchedNode(plan) for plan in self.plans}
        self._http: HttpClient | None = None
        self._started = False
        self._stopping = False
        self._stopped = False
        self._stop_requested = asyncio.Event()
        self._start_idle = asyncio.Event()
        self._start_idle.set()
        self._changed = asyncio.Event()
        self._control_wanted = control
        self._control: Node | None = None
        self._parameters = tuple(parameters)

    # -- public ---------------------------------------------------------------------------------

    async def start(self) -> None:
        """Start every node (the core first, if there are parameters to set on it) and wait until
        each is ready; respawning starts now.

        Raises ``LaunchError`` (after stopping what did start) if a port is taken or a node
        does not become ready in time on its first start. Returns early if a stop is requested.
        """
        if self._started:
            raise LaunchError("this launch was already started; create a new Supervisor")
        self._started = True
        try:
            try:
                self._start_idle.clear()
                check_ports_free(self.plans, self.options)
                self._http = HttpClient()
                self._announce()
                children = list(self._children.values())
                if self._parameters:  # roslaunch's <param>s: on the core's server before any node starts
                    for child in (child for child in children if child.plan.is_core):
                        if self._stopping:
                            return
                        await self._start_first(child)
                    if self._stopping:
                        return
                    await self._set_parameters()
                    children = [child for child in children if not child.plan.is_core]
                await self._start_together(children)
            finally:
                self._start_idle.set()
        except BaseException:
            await self.stop()
            raise
        if not self._stopping:
            self._say(f"all {len(self._children)} nodes up; Ctrl-C stops them")
            if any(plan.is_core for plan in self.plans):
                for line in next_steps(self.core_url):
                    self._say(line)

    async def stop(self) -> None:
        """Stop every node, last started first, and their process groups; safe to call twice."""
        self.request_stop()
        await self._start_idle.wait()
        if self._stopped:
            return
        self._stopped = True
        if self._control is not None:
            await self._control.stop()
        started = [child for child in self._children.values() if child.process is not None]
        running = sum(child.running for child in started)
        if running:
            self._say(f"stopping {running} node{'s' if running != 1 else ''}")
        for child in reversed(started):
            await self._terminate(child, report=True)
            if child.watch is not None:
                try:
                    await child.watch  # returns promptly: it sees the stop request
                except Exception as error:  # a bug there must not leave processes behind
                    self._say(f"supervising {child.plan.name} failed: {error!r}")
            await self._terminate(child)  # a respawn racing the stop request
            child.state = NodeState.STOPPED
        if self._http is not None:
            await self._http.aclose()
        if started:
            self._say("all nodes stopped")
        self._notify()

    def request_stop(self) -> None:
        """Ask for a stop without waiting for it (what the signal handlers do); ``stop`` finishes it."""
        self._stopping = True
        self._stop_requested.set()
        self._notify()

    async def run(self) -> int:
        """Start, supervise until SIGINT/SIGTERM (or ``request_stop``), stop; 0 on a clean stop.

        A second signal while stopping kills every node at once.
        """
        loop = asyncio.get_running_loop()
        handled: list[signal.Signals] = []
        for sig in (signal.SIGINT, signal.SIGTERM):
            with contextlib.suppress(NotImplementedError, RuntimeError, ValueError):
                loop.add_signal_handler(sig, self._on_signal, sig)
                handled.append(sig)
        try:
            await self.start()
            await self._stop_requested.wait()
        finally:
            await self.stop()
            for sig in handled:
                loop.remove_signal_handler(sig)
        return 0

    def status(self, name: str) -> NodeStatus:
        """A snapshot of node ``name``."""
        return self._child(name).status()

    async def wait_ready(self, name: str, *, count: int = 1) -> NodeStatus:
        """Wait until node ``name`` has become ready ``count`` times in all (1: first start).

        Raises ``LaunchError`` if that cannot happen any more: the launch is stopping or the
        node died and is not respawned. Wrap in ``asyncio.timeout`` to bound the wait.
        """
        child = self._child(name)
        while child.ready_count < count:
            if self._stopping:
                raise LaunchError(f"{name} will not become ready: the launch is stopping")
            if child.state in (NodeState.EXITED, NodeState.KILLED):
                raise LaunchError(f"{name} exited (code {child.exit_code}) and is not respawned")
            changed = self._changed
            await changed.wait()
        return self.status(name)

    # -- starting -----------------------------------------------------------------------------

    def _announce(self) -> None:
        nodes = ", ".join(f"{plan.name} :{plan.port}" for plan in self.plans)
        self._say(f"starting {nodes}; core at {self.core_url}")
        notice = self.options.endpoints_notice()
        if notice and any(plan.is_core for plan in self.plans):
            self._say(notice)
        if self._show_seed:
            seed = self.options.seed
            self._say(f"world seed {seed} (--seed {seed} gives the same world again)")

    async def _set_parameters(self) -> None:
        """Put the launch's ROS 1 parameters on the core's parameter server."""
        if not self._parameters or self._http is None:
            return
        server = RosParamClient(self._http, self.core_url)
        try:
            for name, value in self._parameters:
                await server.set(name, value)
        except RosParamError as error:
            raise LaunchError(f"cannot set the launch's parameters: {error}") from None
        count = len(self._parameters)
        self._say(f"set {count} parameter{'s' if count != 1 else ''} on the core's parameter server")

    async def _start_first(self, child: LaunchedNode) -> None:
        await self._spawn(child)
        await self._settle_first(child, await self._wait_healthy(child))

    async def _start_together(self, children: list[LaunchedNode]) -> None:
        """Start ``children`` at once and wait until each is ready (on two cores the launch is up
        in about half the time one after the other takes: a node's start is mostly its imports).
        A node started beside the core waits for it quietly while it starts. A node is ready (and
        watched) as soon as it answers; its ready line waits for those of the nodes before it, so
        they read in launch order. The launch's own node starts last: its imports would take CPU
        from the nodes starting (`skydeck node kill` needs it only once they are up)."""
        core = next((child.plan for child in children if child.plan.is_core), None)
        beside_core = {} if core is None else {"SKYDECK_CORE_START_GRACE_S": f"{core.ready_timeout_s:g}"}
        for child in children:
            if self._stopping:
                return
            await self._spawn(child, {} if child.plan.is_core else beside_core)
        lines: list[str | None] = [None] * len(children)
        said = 0

        async def settle(index: int, child: LaunchedNode) -> Health:
            nonlocal said
            outcome = await self._wait_healthy(child)
            if outcome is Health.READY:
                lines[index] = self._mark_ready(child)
                child.watch = asyncio.create_task(self._watch(child), name=f"launch-watch-{child.plan.name}")
                while said < len(lines) and (line := lines[said]) is not None:
                    self._say(line)
                    said += 1
            return outcome

        outcomes = await asyncio.gather(*(settle(index, child) for index, child in enumerate(children)))
        for child, outcome in zip(children, outcomes, strict=True):  # the first failure, in launch order
            if outcome is not Health.READY:
                await self._settle_first(child, outcome)
        if self._control_wanted and any(plan.is_core for plan in self.plans) and not self._stopping:
            await self._start_control()

    async def _settle_first(self, child: LaunchedNode, outcome: Health) -> None:
        """A first start's outcome: ready (watched from now on), or a LaunchError saying why not."""
        plan = child.plan
        if outcome is Health.READY:
            self._ready(child)
            child.watch = asyncio.create_task(self._watch(child), name=f"launch-watch-{plan.name}")
        elif outcome is Health.EXITED:
            code = await self._reap(child)
            last = f": {child.stderr_tail[-1]}" if child.stderr_tail else ""
            raise LaunchError(
                f"{plan.name} exited with {describe_exit(code)} before it was ready{last}",
                node=plan.name,
                exit_code=code,
                stderr_tail=tuple(child.stderr_tail),
            )
        elif outcome is Health.TIMEOUT:
            raise LaunchError(
                f"{plan.name} (pid {child.pid}) did not answer {plan.url}/health within "
                f"{plan.ready_timeout_s:g} s; is it serving on port {plan.port}?",
                node=plan.name,
                stderr_tail=tuple(child.stderr_tail),
            )

    async def _spawn(self, child: LaunchedNode, extra_env: Mapping[str, str] | None = None) -> None:
        plan = child.plan
        argv = [str(part) for part in self._command_for(plan)]
        env = {
            **self._settings.environment,
            "SKYDECK_CORE_URL": self.core_url,
            "PYTHONUNBUFFERED": "1",
            **(extra_env or {}),
            **plan.env,
        }
        prefix = f"[{plan.name}] "

        def on_line(text: str, is_stderr: bool) -> None:
            if is_stderr and text.strip():
                child.stderr_tail.append(text)
            write_line(self._out, prefix + text)

        process = await spawn(argv, env, on_line, what=plan.name)
        child.process = process
        child.pid = process.pid
        child.started_at = time.monotonic()
        child.starts += 1
        child.state = NodeState.STARTING
        child.stderr_tail.clear()
        self._notify()

    async def _wait_healthy(self, child: LaunchedNode) -> Health:
        """Poll /health until 200, the process exits, the deadline passes or a stop is asked."""
        if self._http is None or child.process is None:
            raise LaunchError("internal: node polled before it was started")
        return await child.process.wait_healthy(
            self._http, f"{child.plan.url}/health", child.plan.ready_timeout_s, lambda: self._stopping
        )

    def _ready(self, child: LaunchedNode) -> None:
        self._say(self._mark_ready(child))

    def _mark_ready(self, child: LaunchedNode) -> str:
        """The node is ready now (waiters are told); the line that says so."""
        child.state = NodeState.READY
        child.ready_count += 1
        took = time.monotonic() - child.started_at
        again = f", restart {child.starts - 1}" if child.starts > 1 else ""
        self._notify()
        return f"{child.plan.name} ready at {child.plan.url} (pid {child.pid}, {took:.1f} s{again})"

    # -- respawning ---------------------------------------------------------------------------

    async def _watch(self, child: LaunchedNode) -> None:
        """After a node's first start: respawn it whenever it dies, until the launch stops."""
        plan = child.plan
        while True:
            if child.exited is None:
                return
            # stop() terminates the process before it awaits this task, so this wait ends too.
            await asyncio.wait({child.exited})
            if self._stopping:
                return
            ran_s = time.monotonic() - child.started_at
            code = await self._reap(child)
            if child.kill_requested:
                child.state = NodeState.KILLED
                self._say(f"{plan.name} killed on request (skydeck node kill); not respawned")
                self._notify()
                return
            if not plan.respawn:
                child.state = NodeState.EXITED
                self._say(
                    f"{plan.name} exited with {describe_exit(code)}; not respawned (respawn: false)"
                )
                self._notify()
                return
            if ran_s >= BACKOFF_RESET_AFTER_S:
                child.backoff_s = BACKOFF_FIRST_S
            self._say(
                f"{plan.name} exited with {describe_exit(code)} after {ran_s:.1f} s; "
                f"respawning in {child.backoff_s:g} s"
            )
            if not await self._respawn(child):
                return

    async def _respawn(self, child: LaunchedNode) -> bool:
        """Restart the node after its backoff until it is ready; False if the launch stops first."""
        plan = child.plan
        while True:
            child.state = NodeState.BACKOFF
            self._notify()
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self._stop_requested.wait(), child.backoff_s)
            if self._stopping:
                return False
            child.backoff_s = min(child.backoff_s * 2, BACKOFF_MAX_S)
            try:
                await self._spawn(child)
            except LaunchError as error:
                self._say(f"{error}; trying again in {child.backoff_s:g} s")
                continue
            outcome = await self._wait_healthy(child)
            if outcome is Health.READY:
                self._ready(child)
                return True
            if outcome is Health.STOPPING:
                return False
            if outcome is Health.EXITED:
                code = await self._reap(child)
                why = f"exited with {describe_exit(code)} before it was ready"
            else:
                await self._terminate(child)
                why = f"did not answer /health within {plan.ready_timeout_s:g} s"
            self._say(f"{plan.name} {why}; respawning in {child.backoff_s:g} s")

    # -- killing on request -------------------------------------------------------------------

    async def kill(self, node: str) -> KillNodeResponse:
        """Stop the child running graph node ``node`` for good (``skydeck node kill``); the
        answer's ``reason`` says what was done or why not (see :func:`~services.launch.control.kill_launched`)."""
        from services.launch.control import kill_launched  # the node SDK: only when asked for

        return await kill_launched(node, self._children, http=self._http, core_url=self.core_url, terminate=self._terminate)

    async def _start_control(self) -> None:
        from services.launch.control import LaunchControl  # the node SDK: only when asked for
        from services.runtime.settings import NodeSettings

        control = LaunchControl(self.kill, NodeSettings(core_url=self.core_url, port=0, host="127.0.0.1"))
        await control.start()
        self._control = control

    # -- stopping -----------------------------------------------------------------------------

    async def _terminate(self, child: LaunchedNode, *, report: bool = False) -> None:
        """SIGTERM the node's process group, SIGKILL it after the stop timeout; then reap."""
        process = child.process
        if process is None:
            return
        was_running = process.running
        code = await process.terminate(
            self._stop_timeout_s,
            on_kill=lambda: self._say(
                f"{child.plan.name} did not stop within {self._stop_timeout_s:g} s; killing it"
            ),
        )
        child.exit_code = code
        if was_running and report:
            self._say(f"{child.plan.name} stopped ({describe_exit(code)})")

    async def _reap(self, child: LaunchedNode) -> int:
        """The exit code of the node's finished process (see ChildProcess.reap)."""
        if child.process is None:
            raise LaunchError("internal: reaping a node that never started")
        child.exit_code = await child.process.reap()
        return child.exit_code

    def _on_signal(self, sig: signal.Signals) -> None:
        if self._stopping:
            self._say(f"{sig.name} again: killing every node now")
            for child in self._children.values():
                if child.running and child.pid is not None:
                    signal_group(child.pid, signal.SIGKILL)
            return
        self._say(f"{sig.name}: stopping")
        self.request_stop()

    # -- output -------------------------------------------------------------------------------

    def _say(self, text: str) -> None:
        say(self._out, text)

    # -- helpers ------------------------------------------------------------------------------

    def _child(self, name: str) -> LaunchedNode:
        try:
            return self._children[name]
        except KeyError:
            raise LaunchError(
                f"no node {name!r} in this launch; its nodes are: {', '.join(self._children)}"
            ) from None

    def _notify(self) -> None:
        """Wake every ``wait_ready`` so it re-checks its condition."""
        self._changed.set()
        self._changed = asyncio.Event()
