"""``rclpy.node.Node``: the class a ROS 2 program subclasses.

    class SendMessageNode(Node):
        def __init__(self):
            super().__init__('send_message_node')
            self.publisher = self.create_publisher(PointStamped, 'my_point', 10)
            self.timer = self.create_timer(0.1, self.run_loop)

A façade over an SDK node (:class:`services.runtime.Node`), which serves its topics, services and
parameters and is in the graph from construction on (as a ROS 2 node is), running on the
bridge's loop. Callbacks run where the program spins the node (:mod:`~services.ros.rclpy.executors`).
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from services.ros.bridge import bridge
from services.ros.errors import NotProvidedError, not_provided
from services.ros.pacing import wait_for_first_clock
from services.ros.rclpy.callback_groups import CallbackGroup, MutuallyExclusiveCallbackGroup
from services.ros.rclpy.client import Client
from services.ros.rclpy.clock import Clock, ROSClock
from services.ros.rclpy.context import Context, default_context
from services.ros.rclpy.logging import RcutilsLogger, node_logger
from services.ros.rclpy.publisher import Publisher
from services.ros.rclpy.qos import qos_profile
from services.ros.rclpy.service import Service
from services.ros.rclpy.subscription import Subscription
from services.ros.rclpy.timer import Rate, Timer
from services.ros.rclpy.waitable import JobQueue, Waitable
from services.ros.tracebacks import user_traceback
from services.runtime.lockstep.activity import ACTIVITY
from services.runtime.node import Node as RuntimeNode
from services.runtime.parameter import Parameter
from shared_models import Message, ServiceType
from shared_models.rcl_interfaces import ParameterDescriptor, SetParametersResult

__all__ = ["Node"]

# rclpy Node methods Skydeck does not have: named, rather than a bare AttributeError.
_NOT_PROVIDED = frozenset(
    {
        "create_guard_condition",
        "create_waitable",
        "add_waitable",
        "get_publishers_info_by_topic",
        "get_subscriptions_info_by_topic",
        "get_type_description_service",
        "set_descriptor",
        "wait_for_node",
    }
)


class Node:
    """A ROS 2 node (see the module docstring); rclpy's constructor keywords are accepted."""

    def __init__(
        self,
        node_name: str,
        *,
        context: Context | None = None,
        cli_args: list[str] | None = None,
        namespace: str | None = None,
        use_global_arguments: bool = True,
        enable_rosout: bool = True,
        start_parameter_services: bool = True,
        parameter_overrides: list[Parameter] | None = None,
        allow_undeclared_parameters: bool = False,
        automatically_declare_parameters_from_overrides: bool = False,
        enable_logger_service: bool = False,
    ) -> None:
        self._rclpy_context = context or default_context
        self._rclpy_context.check("creating a node (rclpy.init() first, as in ROS 2)")
        node = RuntimeNode(
            node_name,
            namespace=namespace,
            cli_args=cli_args,
            use_global_arguments=use_global_arguments,
            parameter_overrides=parameter_overrides,
            allow_undeclared_parameters=allow_undeclared_parameters,
            automatically_declare_parameters_from_overrides=automatically_declare_parameters_from_overrides,
            start_parameter_services=start_parameter_services,
        )
        self._rclpy_node = node
        self._rclpy_executor: Any = None
        self._rclpy_entities: list[Any] = []
        self._rclpy_jobs = JobQueue(self, None, "a done callback")
        self._rclpy_default_group: CallbackGroup = MutuallyExclusiveCallbackGroup()
        self._rclpy_clock = ROSClock(node.get_clock())
        self._rclpy_logger = node_logger(node, rosout=enable_rosout)
        self._rclpy_destroyed = False
        ACTIVITY.watch(self, self._rclpy_has_work)  # a lockstep run waits for its callbacks
        # ...until the node is gone: destroyed, or its context shut down (no executor runs them then)
        this = weakref.ref(self)
        self._rclpy_context.on_shutdown(lambda: _stop_watching(this))
        bridge.start_node(node)
        wait_for_first_clock(node.get_clock())

    def __getattr__(self, name: str) -> Any:
        if name in _NOT_PROVIDED:
            raise NotProvidedError(not_provided(f"Node.{name}"))
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    # -- identity -----------------------------------------------------------------------------

    def get_name(self) -> str:
        """The node's name, without namespace (``send_message_node``), as rclpy's."""
        return self._rclpy_node.get_name().rpartition("/")[2]

    def get_namespace(self) -> str:
        return self._rclpy_node.get_namespace()

    def get_fully_qualified_name(self) -> str:
        return self._rclpy_node.get_name()

    @property
    def context(self) -> Context:
        return self._rclpy_context

    @property
    def executor(self) -> Any:
        return self._rclpy_executor

    @executor.setter
    def executor(self, executor: Any) -> None:
        if executor is None:
            if self._rclpy_executor is not None:
                self._rclpy_executor.remove_node(self)
        else:
            executor.add_node(self)

    @property
    def default_callback_group(self) -> CallbackGroup:
        return self._rclpy_default_group

    def get_logger(self) -> RcutilsLogger:
        """The node's logger: prints, and publishes on /rosout."""
        return self._rclpy_logger

    def get_clock(self) -> Clock:
        """ROS time: sim time when the node's ``use_sim_time`` is set."""
        return self._rclpy_clock

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        return self._rclpy_node._names.expand(topic) if only_expand else self._rclpy_node.resolve_topic_name(topic)

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        return self.resolve_topic_name(service, only_expand=only_expand)

    # -- entities -----------------------------------------------------------------------------

    def create_publisher(
        self, msg_type: type[Message], topic: str, qos_profile_or_depth: Any = None, *,
        callback_group: CallbackGroup | None = None, event_callbacks: Any = None,
        qos_overriding_options: Any = None, publisher_class: Any = None, **kwargs: Any,
    ) -> Publisher:  # fmt: skip
        """``create_publisher(PointStamped, 'my_point', 10)``: a QoS profile or a depth."""
        qos = qos_profile(kwargs.pop("qos_profile", qos_profile_or_depth))
        _no_more(kwargs, "create_publisher")
        _check_message_type(msg_type, "create_publisher")
        runtime = bridge.call(
            lambda: self._rclpy_node.create_publisher(msg_type, topic, qos.queue_depth, latched=qos.latched)
        )
        publisher = Publisher(runtime, qos, self)
        self._rclpy_entities.append(publisher)
        return publisher

    def create_subscription(
        self, msg_type: type[Message], topic: str, callback: Callable[[Any], Any], qos_profile_or_depth: Any = None,
        *, callback_group: CallbackGroup | None = None, event_callbacks: Any = None,
        qos_overriding_options: Any = None, raw: bool = False, **kwargs: Any,
    ) -> Subscription:  # fmt: skip
        """``create_subscription(LaserScan, 'scan', self.process_scan, 10)``."""
        qos = qos_profile(kwargs.pop("qos_profile", qos_profile_or_depth))
        _no_more(kwargs, "create_subscription")
        _check_message_type(msg_type, "create_subscription")
        if not callable(callback):
            raise TypeError(f"create_subscription needs a callback function, got {callback!r}")
        if raw:
            raise NotProvidedError(not_provided("create_subscription(raw=True) (serialised messages)"))
        subscription = Subscription(
            self, msg_type, self.resolve_topic_name(topic), callback, qos, callback_group or self._rclpy_default_group
        )
        bridge.call(lambda: self._rclpy_node.create_subscription(msg_type, topic, subscription._arrived, qos.queue_depth))
        self._rclpy_entities.append(subscription)
        return subscription

    def create_service(
        self, srv_type: type[ServiceType], srv_name: str, callback: Callable[[Any, Any], Any], *,
        qos_profile: Any = None, callback_group: CallbackGroup | None = None,
    ) -> Service:  # fmt: skip
        """``create_service(Trigger, 'reset', self.handle_reset)``: ``callback(request, response)``."""
        _check_service_type(srv_type, "create_service")
        service = Service(
            self, srv_type, self.resolve_service_name(srv_name), callback, callback_group or self._rclpy_default_group
        )
        bridge.call(lambda: self._rclpy_node.create_service(srv_type, srv_name, service._handle))
        self._rclpy_entities.append(service)
        return service

    def create_client(
        self, srv_type: type[ServiceType], srv_name: str, *, qos_profile: Any = None,
        callback_group: CallbackGroup | None = None,
    ) -> Client:  # fmt: skip
        """``create_client(Trigger, 'reset')``: ``call_async``, ``call``, ``wait_for_service``."""
        _check_service_type(srv_type, "create_client")
        runtime = bridge.call(lambda: self._rclpy_node.create_client(srv_type, srv_name))
        client = Client(self, runtime, callback_group or self._rclpy_default_group)
        self._rclpy_entities.append(client)
        return client

    def create_timer(
        self, timer_period_sec: float, callback: Callable[[], Any] | None,
        callback_group: CallbackGroup | None = None, clock: Clock | None = None, autostart: bool = True,
    ) -> Timer:  # fmt: skip
        """``create_timer(0.1, self.run_loop)``: every 0.1 s of the node's clock."""
        if not isinstance(timer_period_sec, int | float) or not timer_period_sec > 0:
            raise ValueError(f"timer_period_sec must be a positive number of seconds, got {timer_period_sec!r}")
        clock = clock or self._rclpy_clock
        timer = Timer(self, callback, float(timer_period_sec), clock, callback_group or self._rclpy_default_group)
        wall = not isinstance(clock, ROSClock)
        timer._timer = bridge.call(
            lambda: self._rclpy_node.create_timer(float(timer_period_sec), timer._tick, wall_clock=wall)
        )
        if not autostart:
            timer.cancel()
        self._rclpy_entities.append(timer)
        return timer

    def create_rate(self, frequency: float, clock: Clock | None = None) -> Rate:
        """``rate = node.create_rate(10)``; ``rate.sleep()`` keeps a loop at 10 Hz."""
        return Rate(frequency, clock or self._rclpy_clock)

    def create_guard_condition(self, callback: Callable[[], Any], callback_group: Any = None) -> Any:
        raise NotProvidedError(not_provided("Node.create_guard_condition"))

    @property
    def publishers(self) -> Iterator[Publisher]:
        return (e for e in self._rclpy_entities if isinstance(e, Publisher))

    @property
    def subscriptions(self) -> Iterator[Subscription]:
        return (e for e in self._rclpy_entities if isinstance(e, Subscription))

    @property
    def timers(self) -> Iterator[Timer]:
        return (e for e in self._rclpy_entities if isinstance(e, Timer))

    @property
    def clients(self) -> Iterator[Client]:
        return (e for e in self._rclpy_entities if isinstance(e, Client))

    @property
    def services(self) -> Iterator[Service]:
        return (e for e in self._rclpy_entities if isinstance(e, Service))

    def destroy_publisher(self, publisher: Publisher) -> bool:
        return self._destroy(publisher)

    def destroy_subscription(self, subscription: Subscription) -> bool:
        return self._destroy(subscription)

    def destroy_timer(self, timer: Timer) -> bool:
        return self._destroy(timer)

    def destroy_client(self, client: Client) -> bool:
        return self._destroy(client)

    def destroy_service(self, service: Service) -> bool:
        return self._destroy(service)

    def destroy_rate(self, rate: Rate) -> bool:
        rate.destroy()
        return True

    def _destroy(self, entity: Any) -> bool:
        if entity not in self._rclpy_entities:
            return False
        self._rclpy_entities.remove(entity)
        entity.destroy()
        return True

    def destroy_node(self) -> None:
        """Leave the graph: the node stops serving; a spin of it returns."""
        if self._rclpy_destroyed:
            return
        self._rclpy_destroyed = True
        ACTIVITY.unwatch(self)
        for timer in list(self.timers):
            timer._due = False
        if self._rclpy_executor is not None:
            self._rclpy_executor.remove_node(self)
        bridge.stop_node(self._rclpy_node)

    # -- the graph ----------------------------------------------------------------------------

    def count_publishers(self, topic_name: str) -> int:
        """Publishers of the topic in the graph, as the core knows them."""
        return len(self._graph_topic(topic_name).get("publishers", []))

    def count_subscribers(self, topic_name: str) -> int:
        return len(self._graph_topic(topic_name).get("subscribers", []))

    def get_topic_names_and_types(self, no_demangle: bool = False) -> list[tuple[str, list[str]]]:
        return [(t["name"], [t["type"]]) for t in self._graph().get("topics", [])]

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        return [(s["name"], [s["type"]]) for s in self._graph().get("services", [])]

    def get_node_names(self) -> list[str]:
        return [n["name"].rpartition("/")[2] for n in self._graph().get("nodes", [])]

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        pairs = []
        for n in self._graph().get("nodes", []):
            namespace, _, name = n["name"].rpartition("/")
            pairs.append((name, namespace or "/"))
        return pairs

    def _graph(self) -> dict[str, Any]:
        node = self._rclpy_node

        async def fetch() -> dict[str, Any]:
            reply = await node.http.get(f"{node.settings.core_url.rstrip('/')}/api/graph", timeout_s=5.0)
            return reply.json() if reply.status == 200 else {}  # type: ignore[no-any-return]

        return bridge.run(fetch())

    def _graph_topic(self, topic_name: str) -> dict[str, Any]:
        name = self.resolve_topic_name(topic_name)
        return next((t for t in self._graph().get("topics", []) if t.get("name") == name), {})

    # -- parameters (the SDK node's; changes run on the bridge's loop, as its services do) -----

    def declare_parameter(
        self, name: str, value: Any = None, descriptor: ParameterDescriptor | None = None,
        ignore_override: bool = False,
    ) -> Parameter:  # fmt: skip
        """Declare ``name`` with its default; its ``--ros-args -p`` override wins."""
        return bridge.call(self._rclpy_node.declare_parameter, name, value, descriptor, ignore_override)

    def declare_parameters(self, namespace: str, parameters: Sequence[Any], ignore_override: bool = False) -> list[Parameter]:
        return bridge.call(self._rclpy_node.declare_parameters, namespace, parameters, ignore_override)

    def undeclare_parameter(self, name: str) -> None:
        bridge.call(self._rclpy_node.undeclare_parameter, name)

    def has_parameter(self, name: str) -> bool:
        return self._rclpy_node.has_parameter(name)

    def get_parameter(self, name: str) -> Parameter:
        return self._rclpy_node.get_parameter(name)

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        return self._rclpy_node.get_parameter_or(name, alternative_value)

    def get_parameters(self, names: Sequence[str]) -> list[Parameter]:
        return self._rclpy_node.get_parameters(names)

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        return self._rclpy_node.get_parameters_by_prefix(prefix)

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        return self._rclpy_node.describe_parameter(name)

    def describe_parameters(self, names: Sequence[str]) -> list[ParameterDescriptor]:
        return self._rclpy_node.describe_parameters(names)

    def set_parameters(self, parameter_list: Sequence[Parameter]) -> list[SetParametersResult]:
        return bridge.call(self._rclpy_node.set_parameters, parameter_list)

    def set_parameters_atomically(self, parameter_list: Sequence[Parameter]) -> SetParametersResult:
        return bridge.call(self._rclpy_node.set_parameters_atomically, parameter_list)

    def add_on_set_parameters_callback(self, callback: Callable[[list[Parameter]], SetParametersResult]) -> Any:
        """``callback(parameters) -> SetParametersResult`` before every change (it may refuse);
        returns the handle ``remove_on_set_parameters_callback`` takes."""
        bridge.call(self._rclpy_node.add_on_set_parameters_callback, callback)
        return callback

    def remove_on_set_parameters_callback(self, callback: Any) -> None:
        bridge.call(self._rclpy_node.remove_on_set_parameters_callback, callback)

    def add_post_set_parameters_callback(self, callback: Callable[[list[Parameter]], None]) -> Any:
        bridge.call(self._rclpy_node.add_post_set_parameters_callback, callback)
        return callback

    def remove_post_set_parameters_callback(self, callback: Any) -> None:
        bridge.call(self._rclpy_node.remove_post_set_parameters_callback, callback)

    # -- for the executor ---------------------------------------------------------------------

    def _rclpy_set_executor(self, executor: Any) -> None:
        self._rclpy_executor = executor

    def _rclpy_waitables(self) -> list[Waitable]:
        return [e for e in self._rclpy_entities if isinstance(e, Waitable)] + [self._rclpy_jobs]

    def _rclpy_has_work(self) -> bool:
        """Whether a callback of this node waits for the executor (a lockstep run waits for it)."""
        return any(entity._has_work() for entity in self._rclpy_waitables())

    def _rclpy_dispatch(self, job: Callable[[], Any]) -> None:
        """Run ``job`` in the executor spinning this node (at once, where none does)."""
        if self._rclpy_executor is None:
            job()
        else:
            self._rclpy_jobs.put(job)

    def _rclpy_report(self, error: BaseException, what: str) -> None:
        """A user callback raised: their traceback, and the node keeps running."""
        self._rclpy_logger.error(f"{what} raised (the node keeps running):\n{user_traceback(error)}")


def _check_message_type(msg_type: Any, verb: str) -> None:
    if not (isinstance(msg_type, type) and issubclass(msg_type, Message) and msg_type.__ros_type__):
        raise TypeError(f"{verb} needs a message type such as geometry_msgs.msg.Twist, got {msg_type!r}")


def _check_service_type(srv_type: Any, verb: str) -> None:
    if not (isinstance(srv_type, type) and issubclass(srv_type, ServiceType)):
        raise TypeError(f"{verb} needs a service type such as std_srvs.srv.Trigger, got {srv_type!r}")


def _no_more(kwargs: dict[str, Any], verb: str) -> None:
    if kwargs:
        raise TypeError(f"{verb}() got unexpected keyword arguments: {', '.join(kwargs)}")


def _stop_watching(node: weakref.ref[Node]) -> None:
    alive = node()
    if alive is not None:
        ACTIVITY.unwatch(alive)
