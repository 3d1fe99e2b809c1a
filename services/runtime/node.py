"""The Node: rclpy's shape (``create_publisher``, ``create_subscription``, ``create_timer``...),
asyncio underneath.

Entities may be created before the node spins (in ``__init__``, as in rclpy) or while it runs.
A running node serves its topics and services over HTTP/WebSocket, stays registered with the
core, and keeps one link per remote publisher of each topic it subscribes to.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import socket
from collections.abc import Callable, Coroutine
from typing import Any, TypeVar

import uvicorn
from pydantic import ValidationError

from services.runtime.app import NodeApp
from services.runtime.client import Client
from services.runtime.clock import Clock
from services.runtime.endpoint import TopicEndpoint
from services.runtime.errors import NodeError
from services.runtime.http_client import HttpClient
from services.runtime.links import PublisherLink
from services.runtime.logger import NodeLogger
from services.runtime.protocol import Entity, NodeDescription, PublisherAddress
from services.runtime.publisher import Publisher
from services.runtime.service import Service
from services.runtime.session import CoreSession, RegistrationRejected
from services.runtime.settings import NodeSettings, reachable_host
from services.runtime.subscription import Subscription
from services.runtime.timer import Timer
from shared_models import Message, ServiceType, resolve_name, resolve_node_name
from shared_models.builtin_interfaces import Time
from shared_models.rcl_interfaces import Log

__all__ = ["Node"]

M = TypeVar("M", bound=Message)

_ROSOUT = "/rosout"
_CLOCK = "/clock"
_SHUTDOWN_GRACE_S = 2.0


class _QuietServer(uvicorn.Server):
    """uvicorn without its own signal handling: the node owns Ctrl-C and SIGTERM."""

    @contextlib.contextmanager
    def capture_signals(self):  # type: ignore[no-untyped-def]
        yield


class Node:
    """A Skydeck node, written like an rclpy node::

        class SendMessageNode(Node):
            def __init__(self):
                super().__init__("send_message_node")
                self.publisher = self.create_publisher(PointStamped, "/my_point", 10)
                self.create_timer(0.1, self.run_loop)

    and run with ``spin(SendMessageNode())``.
    """

    def __init__(self, node_name: str, *, settings: NodeSettings | None = None) -> None:
        self.settings = settings or NodeSettings()
        self._name = resolve_node_name(node_name)
        self.pid = os.getpid()
        self._clock = Clock(use_sim_time=self.settings.use_sim_time)
        self._endpoints: dict[str, TopicEndpoint] = {}
        self._services: dict[str, Service] = {}
        self._timers: list[Timer] = []
        self._subscriptions: list[Subscription] = []
        self._links: dict[tuple[str, str], tuple[PublisherLink, asyncio.Task[None]]] = {}
        self._tasks: set[asyncio.Task[Any]] = set()
        self._app = NodeApp(self)
        self._url = ""
        self._running = False
        self._destroyed = False
        self._stopping: asyncio.Event | None = None
        self._session: CoreSession | None = None
        self._http: HttpClient | None = None
        self._rosout = self.create_publisher(Log, _ROSOUT, 100)
        self._logger = NodeLogger(self._name, self._stamp, self._rosout.publish, level=self.settings.log_level)
        if self.settings.use_sim_time:
            self.create_subscription(Time, _CLOCK, self._clock.set_sim_time, 1)

    # -- identity -----------------------------------------------------------------------------

    def get_name(self) -> str:
        """The node's name, with its leading slash (``/send_message_node``)."""
        return self._name

    @property
    def url(self) -> str:
        """The URL other processes reach this node at (empty until it serves)."""
        return self._url

    def get_logger(self) -> NodeLogger:
        """The node's logger; every line also goes to ``/rosout``."""
        return self._logger

    def get_clock(self) -> Clock:
        """The node's clock: sim time when ``use_sim_time`` is set, else wall time."""
        return self._clock

    def _stamp(self) -> Time:
        return self._clock.now().to_msg()

    # -- entities -----------------------------------------------------------------------------

    def create_publisher(
        self, msg_type: type[M], topic: str, qos_profile: int = 10, *, latched: bool = False
    ) -> Publisher[M]:
        """A publisher of ``msg_type`` on ``topic``; ``qos_profile`` is the queue depth.

        ``latched=True`` sends the latest message to every new subscriber at once (ROS 1's latch).
        """
        endpoint = self._endpoint(msg_type, topic)
        endpoint.publishing = True
        endpoint.latched = endpoint.latched or latched
        publisher = Publisher(endpoint, msg_type, _depth(qos_profile))
        self._changed()
        return publisher

    def create_subscription(
        self, msg_type: type[M], topic: str, callback: Callable[[M], Any], qos_profile: int = 10
    ) -> Subscription:
        """Call ``callback(msg)`` for every message on ``topic``; ``qos_profile`` is the queue depth."""
        endpoint = self._endpoint(msg_type, topic)
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
        name = resolve_name(srv_name)
        if name in self._services or name in self._endpoints:
            raise NodeError(f"{self._name} already has a topic or service named {name}")
        service = Service(srv_type, name, callback)
        self._services[name] = service
        self._app.add_service(service)
        self._changed()
        return service

    def create_client(self, srv_type: type[ServiceType], srv_name: str) -> Client[Any]:
        """A client of ``srv_name``: ``await client.call(request, timeout_s=5)``."""
        self._check_alive()
        return Client(
            srv_type,
            resolve_name(srv_name),
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

    def destroy_node(self) -> None:
        """Stop the node; creating entities afterwards raises NodeError."""
        self._destroyed = True
        if self._stopping is not None:
            self._stopping.set()

    def _check_alive(self) -> None:
        if self._destroyed:
            raise NodeError(f"node {self._name} is destroyed: create a new node instead")

    def _endpoint(self, msg_type: type[Message], topic: str) -> TopicEndpoint:
        self._check_alive()
        if not (isinstance(msg_type, type) and issubclass(msg_type, Message) and msg_type.__ros_type__):
            raise TypeError(f"expected a message type such as PointStamped, got {msg_type!r}")
        name = resolve_name(topic)
        endpoint = self._endpoints.get(name)
        if endpoint is None:
            if name in self._services:
                raise NodeError(f"{self._name} already has a service named {name}")
            endpoint = TopicEndpoint(name, msg_type)
            self._endpoints[name] = endpoint
            self._app.add_topic(endpoint)
        elif endpoint.msg_type is not msg_type:
            raise NodeError(
                f"{name} is already used with type {endpoint.type_name} in {self._name}, "
                f"not {msg_type.__ros_type__}"
            )
        return endpoint

    def _changed(self) -> None:
        if self._session is not None:
            self._session.mark_changed()

    def _inject(self, endpoint: TopicEndpoint, msg: Message) -> None:
        """A client published ``msg`` on this node's stream of ``endpoint``."""
        if endpoint.publishing:
            endpoint.dispatch(msg, msg.model_dump_json())
        else:
            endpoint.receive(msg, msg.model_dump_json())

    # -- registry -----------------------------------------------------------------------------

    def describe(self) -> NodeDescription:
        """What this node tells the core about itself."""
        publications, subscriptions = [], []
        for endpoint in self._endpoints.values():
            entity = Entity(name=endpoint.name, type=endpoint.type_name, latched=endpoint.latched)
            if endpoint.publishing:
                publications.append(entity)
            if endpoint.subscriptions:
                subscriptions.append(entity)
        services = [Entity(name=s.name, type=s.srv_type.__ros_type__) for s in self._services.values()]
        return NodeDescription(
            name=self._name,
            url=self._url,
            pid=self.pid,
            publications=publications,
            subscriptions=subscriptions,
            services=services,
        )

    def _published_counts(self) -> dict[str, int]:
        return {e.name: e.published_count for e in self._endpoints.values() if e.publishing}

    def _set_publishers(self, topic: str, publishers: list[PublisherAddress]) -> None:
        """The core's list of publishers of ``topic`` changed: connect and disconnect links."""
        endpoint = self._endpoints.get(topic)
        if endpoint is None or not endpoint.subscriptions:
            return
        wanted = {p.url.rstrip("/") for p in publishers} - {self._url}
        for key in [key for key in self._links if key[0] == topic and key[1] not in wanted]:
            self._links.pop(key)[1].cancel()
        queue_size = max(s.queue_size for s in endpoint.subscriptions)
        for url in wanted:
            if (topic, url) not in self._links:
                link = PublisherLink(
                    url,
                    topic,
                    self._frame_receiver(endpoint),
                    queue_size=queue_size,
                    max_message_bytes=self.settings.max_message_bytes,
                    ping_interval_s=self.settings.ping_interval_s,
                    ping_timeout_s=self.settings.ping_timeout_s,
                    token=self.settings.token,
                )
                self._links[(topic, url)] = (link, self._spawn(link.run()))

    def _frame_receiver(self, endpoint: TopicEndpoint) -> Callable[[str], None]:
        parse = endpoint.msg_type.model_validate_json
        receive = endpoint.receive
        logger = self._logger.logger

        def on_frame(frame: str) -> None:
            try:
                msg = parse(frame)
            except ValidationError as error:
                logger.warning("dropped a message on %s that is not a %s: %s", endpoint.name, endpoint.type_name, error)
                return
            receive(msg, frame)

        return on_frame

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
        sock = _bind(self.settings.host, self.settings.port)
        port = sock.getsockname()[1]
        self._url = (self.settings.advertise_url or f"http://{reachable_host(self.settings.host)}:{port}").rstrip("/")
        config = uvicorn.Config(
            self._app.fastapi,
            log_level="warning",
            access_log=False,
            lifespan="off",
            ws_max_size=self.settings.max_message_bytes,
            ws_ping_interval=self.settings.ping_interval_s,
            ws_ping_timeout=self.settings.ping_timeout_s,
            ws_per_message_deflate=False,
        )
        self._server = _QuietServer(config)
        self._server_task = asyncio.get_running_loop().create_task(self._server.serve(sockets=[sock]))
        while not self._server.started:
            if self._server_task.done():
                await self._server_task
                raise NodeError(f"{self._name} could not start serving on port {port}")
            await asyncio.sleep(0.005)
        self._running = True
        self._http = HttpClient(
            headers={"Authorization": f"Bearer {self.settings.token}"} if self.settings.token else None
        )
        self._session = CoreSession(
            self.settings.core_url,
            describe=self.describe,
            stats=self._published_counts,
            on_publishers=self._set_publishers,
            token=self.settings.token,
        )
        self._spawn(self._session.run())
        for subscription in self._subscriptions:
            self._spawn(subscription.run(self._logger.logger))
        for timer in self._timers:
            self._spawn(timer.run(self._logger.logger))

    async def stop(self) -> None:
        """Stop serving and end every task of the node."""
        if not self._running:
            return
        self._running = False
        for task in list(self._tasks):
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)
        self._links.clear()
        self._server.should_exit = True
        try:
            # In-flight requests get a moment to finish; a handler that hangs does not hang us.
            await asyncio.wait_for(asyncio.shield(self._server_task), _SHUTDOWN_GRACE_S)
        except TimeoutError:
            self._server.force_exit = True
            await self._server_task
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


def _bind(host: str, port: int) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    # IPPROTO_TCP, not 0: asyncio sets TCP_NODELAY only on sockets that say they are TCP, and
    # without it Nagle + delayed ACK hold every small HTTP reply for ~40 ms.
    sock = socket.socket(family, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
    except OSError as error:
        sock.close()
        raise NodeError(f"cannot listen on {host}:{port}: {error.strerror} (is another node using it? pick --port)") from None
    sock.listen(128)
    sock.setblocking(False)
    return sock


