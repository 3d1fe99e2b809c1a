"""The Node: rclpy's shape (``create_publisher``, ``create_subscription``, ``create_timer``...),
asyncio underneath.

Entities may be created before the node spins (in ``__init__``, as in rclpy) or while it runs.
A running node serves its topics and services over HTTP/WebSocket, stays registered with the
core, and keeps one link per remote publisher of each topic it subscribes to.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Coroutine
from typing import Any, Literal, TypeVar

from services.runtime.app import NodeApp
from services.runtime.client import Client
from services.runtime.clock import Clock
from services.runtime.edge.encoding import Encoding
from services.runtime.errors import NodeError
from services.runtime.http_client import HttpClient
from services.runtime.lockstep import agent as lockstep
from services.runtime.logger import NodeLogger
from services.runtime.node_parameters import ParametersMixin
from services.runtime.parameter import Parameter
from services.runtime.parameter_service import PARAMETER_EVENTS, parameter_services
from services.runtime.parameters import NodeParameters
from services.runtime.participant import Participant
from services.runtime.protocol import ForeignNode
from services.runtime.publisher import Publisher
from services.runtime.ros_args import (
    ROS_ARGS,
    NameResolver,
    RosArguments,
    parse_ros_args,
    process_ros_arguments,
    split_ros_args,
)
from services.runtime.server import AppServer
from services.runtime.service import Service
from services.runtime.session import CoreSession, RegistrationRejected
from services.runtime.settings import NodeSettings, node_settings, reachable_host
from services.runtime.subscription import RawSubscription, Subscription
from services.runtime.timer import Timer
from shared_models import Message, ServiceType, resolve_node_name
from shared_models.builtin_interfaces import Time, split_seconds
from shared_models.rcl_interfaces import Log, ParameterDescriptor, ParameterEvent

__all__ = ["Node"]

M = TypeVar("M", bound=Message)

_ROSOUT = "/rosout"
_CLOCK = "/clock"


class Node(ParametersMixin):
    """A Skydeck node, written like an rclpy node::

        class SendMessageNode(Node):
            def __init__(self):
                super().__init__("send_message_node")
                self.publisher = self.create_publisher(PointStamped, "/my_point", 10)
                self.create_timer(0.1, self.run_loop)

    and run with ``spin(SendMessageNode())``. The node is the API; what it publishes, subscribes
    to and serves lives in its :class:`~services.runtime.participant.Participant`, served by its
    own uvicorn (:class:`~services.runtime.server.AppServer`) and registered over a
    :class:`~services.runtime.session.CoreSession`.

    Parameters (:mod:`services.runtime.node_parameters`) take their overrides from this
    process's ``--ros-args`` (unless ``use_global_arguments=False``), then ``cli_args``, then
    ``parameter_overrides``; every node serves them as ROS 2's parameter services. The same
    arguments' remap rules (``-r scan:=/robot1/scan``, ``-r __ns:=/robot1``, ``-r __node:=x``)
    apply to every name the node resolves (:class:`~services.runtime.ros_args.NameResolver`).
    """

    def __init__(
        self,
        node_name: str,
        *,
        namespace: str | None = None,
        settings: NodeSettings | None = None,
        cli_args: list[str] | None = None,
        use_global_arguments: bool = True,
        parameter_overrides: list[Parameter] | None = None,
        allow_undeclared_parameters: bool = False,
        automatically_declare_parameters_from_overrides: bool = False,
        start_parameter_services: bool = True,
    ) -> None:
        self.settings = settings or node_settings()
        arguments = process_ros_arguments() if use_global_arguments else RosArguments()
        if cli_args:  # rclpy's form (["--ros-args", "-r", ...]) or the ROS arguments alone
            ros_part = split_ros_args(cli_args)[1] if ROS_ARGS in cli_args else cli_args
            arguments = arguments + parse_ros_args(ros_part)
        program_name = resolve_node_name(node_name).lstrip("/")
        self._names = NameResolver(
            arguments.namespace_for(program_name) or namespace or "/",
            arguments.node_name_for(program_name),
            arguments.remaps_for(program_name),
        )
        self._name = self._names.full_node_name
        self._clock = Clock(use_sim_time=self.settings.use_sim_time)
        self._clock.driven = bool(self.settings.lockstep_url)
        self._app = NodeApp(
            self._name,
            token=self.settings.token,
            max_message_bytes=self.settings.max_message_bytes,
            stall_timeout_s=self.settings.reader_stall_s,
            health=lambda: {"status": "ok", "node": self._name, "pid": self.pid},
        )
        self._participant = Participant(
            self._name,
            self.settings,
            on_endpoint=self._app.add_topic,
            on_service=self._app.add_service,
            on_changed=self._changed,
        )
        self._participant.in_lockstep = bool(self.settings.lockstep_url)
        self._timers: list[Timer] = []
        self._subscriptions: list[Subscription] = []
        self._tasks: set[asyncio.Task[Any]] = set()
        self._running = False
        self._destroyed = False
        self._stopping: asyncio.Event | None = None
        self._session: CoreSession | None = None
        self._server: AppServer | None = None
        self._http: HttpClient | None = None
        self._rosout = self.create_publisher(Log, _ROSOUT, 100)
        self._logger = NodeLogger(self._name, self._stamp, self._rosout.publish, level=self.settings.log_level)
        self._clock_subscription: Subscription | RawSubscription | None = None
        self._parameter_events = self.create_publisher(ParameterEvent, PARAMETER_EVENTS, 1000)
        overrides: dict[str, Any] = arguments.overrides_for(self._name)
        overrides.update({p.name: p for p in parameter_overrides or ()})
        self._parameters = NodeParameters(
            self._name,
            overrides=overrides,
            allow_undeclared_parameters=allow_undeclared_parameters,
            on_event=self._publish_parameter_event,
        )
        self._parameters.post_set_callbacks.append(self._parameters_changed)
        self.declare_parameter(
            "use_sim_time",
            self.settings.use_sim_time,
            ParameterDescriptor(description="follow /clock (the simulator's time) instead of the wall clock"),
        )
        if automatically_declare_parameters_from_overrides:
            for name, value in overrides.items():
                if not self.has_parameter(name):
                    self.declare_parameter(name, value)
        if start_parameter_services:
            for srv_type, srv_name, handler in parameter_services(self._name, self._parameters, self._logger.logger):
                self.create_service(srv_type, srv_name, handler)

    # -- identity -----------------------------------------------------------------------------

    def get_name(self) -> str:
        """The node's full name, with its leading slash and namespace (``/send_message_node``)."""
        return self._name

    def get_namespace(self) -> str:
        """The node's namespace (``/`` for none; ``-r __ns:=/robot1`` sets it)."""
        return self._names.namespace

    def resolve_topic_name(self, topic: str) -> str:
        """The graph's name for ``topic`` as this node uses it: expanded in its namespace
        (``~/x`` under its own name) and remapped."""
        return self._names.resolve(topic)

    resolve_service_name = resolve_topic_name

    @property
    def pid(self) -> int:
        return self._participant.pid

    @property
    def url(self) -> str:
        """The URL other processes reach this node at (empty until it serves)."""
        return self._participant.url

    def get_logger(self) -> NodeLogger:
        """The node's logger; every line also goes to ``/rosout``."""
        return self._logger

    @property
    def rosout_publisher(self) -> Publisher[Log]:
        """The node's publisher of ``/rosout`` (a façade's logger publishes through it)."""
        return self._rosout

    def get_clock(self) -> Clock:
        """The node's clock: sim time when ``use_sim_time`` is set, else wall time."""
        return self._clock

    def _stamp(self) -> Time:
        return self._clock.now().to_msg()

    def _publish_parameter_event(self, event: ParameterEvent) -> None:
        event.stamp = self._stamp()
        self._parameter_events.publish(event)

    def _parameters_changed(self, parameters: list[Parameter]) -> None:
        for parameter in parameters:
            if parameter.name == "use_sim_time":
                self._use_sim_time(bool(parameter.value))

    def _use_sim_time(self, enabled: bool) -> None:
        """Switch the clock (timers follow within a period); /clock is subscribed on first use."""
        self._clock.set_use_sim_time(enabled)
        if enabled and self._clock_subscription is None and not self._clock.driven:
            self._clock_subscription = self.create_subscription(Time, _CLOCK, self._clock.set_sim_time, 1)

    # -- entities -----------------------------------------------------------------------------

    def create_publisher(
        self, msg_type: type[M], topic: str, qos_profile: int = 10, *, latched: bool = False
    ) -> Publisher[M]:
        """A publisher of ``msg_type`` on ``topic``; ``qos_profile`` is the queue depth.

        ``latched=True`` sends the latest message to every new subscriber at once (ROS 1's latch).
        """
        self._check_alive()
        endpoint = self._participant.endpoint(msg_type, self._names.resolve(topic))
        endpoint.publishing = True
        endpoint.latched = endpoint.latched or latched
        publisher = Publisher(endpoint, msg_type, _depth(qos_profile))
        self._changed()
        return publisher

    def create_subscription(
        self,
        msg_type: type[M],
        topic: str,
        callback: Callable[[M], Any] | Callable[[str], Any] | Callable[[bytes], Any],
        qos_profile: int = 10,
        *,
        raw: bool = False,
        raw_encoding: Literal["json", "msgpack"] = "json",
    ) -> Subscription | RawSubscription:
        """Call ``callback(msg)`` for every message on ``topic``; ``qos_profile`` is the queue depth.

        ``raw=True`` (as rclpy's): ``callback(frame)`` gets each message's JSON text as received,
        unparsed; it runs where the frame arrives, so it must be quick (a recorder's write).
        ``raw_encoding="msgpack"`` gets the msgpack bytes links carry instead (byte arrays as
        bytes, not base64: the ROS 2 bridge's way to a camera's images).
        """
        self._check_alive()
        endpoint = self._participant.endpoint(msg_type, self._names.resolve(topic))
        if raw:
            encoding = Encoding.MSGPACK if raw_encoding == "msgpack" else Encoding.JSON
            tap = RawSubscription(endpoint.name, msg_type, callback, _depth(qos_profile), encoding)  # type: ignore[arg-type]
            endpoint.taps.add(tap)
            self._changed()
            return tap
        subscription = Subscription(endpoint.name, msg_type, callback, _depth(qos_profile))
        endpoint.subscriptions.append(subscription)
        self._subscriptions.append(subscription)
        if self._running:
            self._spawn(subscription.run(self._logger.logger))
        self._changed()
        return subscription

    def create_service(
        self, srv_type: type[ServiceType], srv_name: str, callback: Callable[..., Any]
    ) -> Service:
        """Serve ``srv_name``: ``callback(request)`` (rospy) or ``callback(request, response)`` (rclpy)."""
        self._check_alive()
        if not (isinstance(srv_type, type) and issubclass(srv_type, ServiceType)):
            raise TypeError(f"create_service needs a service type such as Trigger, got {srv_type!r}")
        service = Service(srv_type, self._names.resolve(srv_name), callback)
        self._participant.add_service(service)
        return service

    def create_client(self, srv_type: type[ServiceType], srv_name: str) -> Client[Any]:
        """A client of ``srv_name``: ``await client.call(request, timeout_s=5)``."""
        self._check_alive()
        return Client(
            srv_type,
            self._names.resolve(srv_name),
            http=lambda: self.http,
            core_url=self.settings.core_url,
            default_timeout_s=self.settings.service_timeout_s,
        )

    def create_timer(
        self, timer_period_sec: float, callback: Callable[[], Any], *, wall_clock: bool = False
    ) -> Timer:
        """Call ``callback()`` every ``timer_period_sec`` on the node's clock (or the wall clock)."""
        self._check_alive()
        timer = Timer(timer_period_sec, callback, Clock() if wall_clock else self._clock)
        self._timers.append(timer)
        if self._running:
            self._spawn(timer.run(self._logger.logger))
        return timer

    def is_linked(self, topic: str) -> bool:
        """Whether this node receives ``topic`` (resolved as its subscriptions are) from at least
        one publisher now."""
        return self._participant.is_linked(self._names.resolve(topic))

    def destroy_node(self) -> None:
        """Stop the node; creating entities afterwards raises NodeError."""
        self._destroyed = True
        if self._stopping is not None:
            self._stopping.set()

    def _check_alive(self) -> None:
        if self._destroyed:
            raise NodeError(f"node {self._name} is destroyed: create a new node instead")

    def _changed(self) -> None:
        if self._session is not None:
            self._session.mark_changed()

    def set_foreign_participants(self, participants: list[ForeignNode]) -> None:
        """Say which participants of another system this node bridges to (a ROS 2 bridge's ROS 2
        nodes): the graph lists them, marked with their system, until this node leaves."""
        if participants != self._participant.foreign:
            self._participant.foreign = list(participants)
            self._changed()

    def lockstep_state(self) -> tuple[bool, list[tuple[str, str, int]], list[tuple[str, str, int]]]:
        """For a lockstep run (:mod:`services.runtime.lockstep`): whether the node has work now
        (a message or a due timer waiting for its callback, a callback running, a link
        connecting), and the messages it sent and received, per topic and node at the other end."""
        busy = any(not s.idle for s in self._subscriptions) or any(t.busy for t in self._timers)
        sent, received, connecting = self._participant.lockstep_counts()
        return busy or connecting, sent, received

    def lockstep_set_clock(self, time_s: float) -> None:
        """For a lockstep run: move the node's sim clock to ``time_s`` (its timers fire as on a
        /clock message); nothing when the node runs on the wall clock."""
        if self._clock.use_sim_time:
            sec, nanosec = split_seconds(time_s)
            self._clock.set_sim_time(Time(sec=sec, nanosec=nanosec))

    def describe(self):  # type: ignore[no-untyped-def]
        """What this node tells the core about itself (a NodeDescription)."""
        return self._participant.describe()

    # -- running ------------------------------------------------------------------------------

    def _spawn(self, coroutine: Coroutine[Any, Any, Any]) -> asyncio.Task[Any]:
        task = asyncio.get_running_loop().create_task(coroutine)
        self._tasks.add(task)
        task.add_done_callback(self._task_done)
        return task

    def _task_done(self, task: asyncio.Task[Any]) -> None:
        self._tasks.discard(task)
        if task.cancelled():
            return
        error = task.exception()
        if isinstance(error, RegistrationRejected):
            self._logger.error("the core refused %s: %s; stopping", self._name, error)
            self.destroy_node()
        elif error is not None:
            self._logger.logger.error("internal task of %s failed", self._name, exc_info=error)

    async def start(self) -> None:
        """Serve, register with the core, and start timers and subscriptions."""
        if self._running:
            raise NodeError(f"node {self._name} is already running")
        self._check_alive()
        self._stopping = asyncio.Event()
        self._server = AppServer(self._app.fastapi, self.settings, what=self._name)
        await self._server.start()
        host = reachable_host(self.settings.host)
        self._participant.url = (self.settings.advertise_url or f"http://{host}:{self._server.port}").rstrip("/")
        self._running = True
        self._http = HttpClient(
            headers={"Authorization": f"Bearer {self.settings.token}"} if self.settings.token else None
        )
        self._participant.start_links(self._spawn)
        self._session = CoreSession(
            self.settings.core_url,
            describe=self._participant.describe,
            stats=self._participant.published_counts,
            on_publishers=self._participant.set_publishers,
            on_key=self._app.accept_core_key,
            token=self.settings.token,
            quiet_s=self.settings.core_start_grace_s,
        )
        self._spawn(self._session.run())
        for subscription in self._subscriptions:
            self._spawn(subscription.run(self._logger.logger))
        for timer in self._timers:
            self._spawn(timer.run(self._logger.logger))
        if self.settings.lockstep_url:
            lockstep.join(self, self.settings.lockstep_url)

    async def stop(self) -> None:
        """Stop serving and end every task of the node."""
        if not self._running:
            return
        self._running = False
        await lockstep.leave(self)
        self._participant.stop_links()
        for task in list(self._tasks):
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)
        if self._server is not None:
            await self._server.stop()
        if self._http is not None:
            await self._http.aclose()

    async def run_until_stopped(self) -> None:
        """Start, run until :meth:`destroy_node` (or a signal, under ``spin``), then stop."""
        await self.start()
        try:
            if self._stopping is not None:
                await self._stopping.wait()
        finally:
            await self.stop()

    @property
    def http(self) -> HttpClient:
        """The node's HTTP client (for service clients); only while running."""
        if self._http is None:
            raise NodeError(f"node {self._name} is not running: service calls need `spin(node)` first")
        return self._http


def _depth(qos_profile: Any) -> int:
    depth = getattr(qos_profile, "depth", qos_profile)
    if not isinstance(depth, int) or isinstance(depth, bool) or depth < 1:
        raise ValueError(f"queue size must be a positive integer, got {qos_profile!r}")
    return depth
