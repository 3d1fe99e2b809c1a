"""``rospy.Service``, ``rospy.ServiceProxy`` and ``rospy.wait_for_service``.

    rospy.Service("/control/take_off", Trigger, handleTakeOffRequest)   # handler(request) -> response

    rospy.wait_for_service("/control/fly", timeout=5)
    fly = rospy.ServiceProxy("/control/fly", FlyCommand)
    response = fly(x, y)                  # request fields in order, or fly(x=1.0, y=2.0), or fly(request)

As in rospy, each request runs the handler on a thread of its own, and a proxy's call blocks
the calling thread (main thread or a callback's: the bridge's loop carries it, so nothing
deadlocks). A handler may return the response, a dict of its fields, a tuple or list of them in
order, or the one value of a one-field response; None is an error, as rospy says. A call that
gets no answer, or an answer that is an error, raises ``rospy.ServiceException``.
"""

from __future__ import annotations

import concurrent.futures
import json
import threading
from collections.abc import Callable
from typing import Any

from pydantic import ValidationError

from services.ros.bridge import Bridge, bridge
from services.ros.rospy.core import process, report
from services.ros.rospy.exceptions import ROSException, ROSInterruptException, ServiceException
from services.runtime.client import Client
from services.runtime.errors import ServiceCallRejectedError, ServiceError
from services.runtime.service import ServiceHandlerError
from shared_models import Message, ServiceType
from shared_models.builtin_interfaces import Duration as DurationMsg

__all__ = ["Service", "ServiceProxy", "response_from", "wait_for_service"]


def _check_service_class(service_class: Any, what: str) -> None:
    if not (isinstance(service_class, type) and issubclass(service_class, ServiceType)):
        raise TypeError(f"{what} needs a service class such as std_srvs.srv.Trigger, got {service_class!r}")


def response_from(result: Any, response_class: type[Message], name: str) -> Message:
    """The response a handler's return value stands for, as rospy reads it; ServiceHandlerError
    (the caller's ServiceException) for what it cannot."""
    try:
        if isinstance(result, response_class):
            return result
        if result is None:
            raise ServiceHandlerError(f"service [{name}]: the handler returned None, not a response")
        if isinstance(result, dict):
            return response_class(**result)
        if isinstance(result, list | tuple):
            return response_class(*result)
        if len(response_class.model_fields) == 1:
            return response_class(result)
    except (TypeError, ValidationError) as error:
        raise ServiceHandlerError(f"service [{name}]: the handler returned an invalid value: {error}") from None
    raise ServiceHandlerError(
        f"service [{name}]: the handler returned {type(result).__name__}, not a {response_class.__name__}"
    )


class Service:
    """Answers ``name`` with ``handler(request)`` (see the module docstring)."""

    def __init__(
        self, name: str, service_class: type[ServiceType], handler: Callable[[Any], Any], buff_size: int = 65536,
        error_handler: Callable[..., Any] | None = None,
    ) -> None:  # fmt: skip
        node = process.require_node("rospy.Service")
        _check_service_class(service_class, "rospy.Service")
        if not callable(handler):
            raise TypeError(f"rospy.Service's handler must be a function, got {handler!r}")
        self.service_class = service_class
        self.handler = handler
        self.resolved_name = node.resolve_service_name(name)
        self._shut_down = False
        bridge.call(lambda: node.create_service(service_class, name, self._handle))

    async def _handle(self, request: Message) -> Message:
        """The SDK's handler (on the bridge's loop): the user's runs on a thread of its own."""
        return await Bridge.hand_off(self._in_a_thread, lambda: self._answer(request))

    def _in_a_thread(self, job: Callable[[], None]) -> None:
        threading.Thread(target=job, name=f"rospy service {self.resolved_name}", daemon=True).start()

    def _answer(self, request: Message) -> Message:
        if self._shut_down:
            raise ServiceHandlerError(f"service [{self.resolved_name}] was shut down")
        try:
            result = self.handler(request)
        except ServiceException as error:  # the handler's own refusal: no traceback, as rospy
            raise ServiceHandlerError(f"service [{self.resolved_name}]: {error}") from None
        except Exception as error:
            report(error, f"the service handler of {self.resolved_name}")
            raise ServiceHandlerError(
                f"service [{self.resolved_name}]: error processing request: {type(error).__name__}: {error}"
            ) from None
        return response_from(result, self.service_class.Response, self.resolved_name)

    def shutdown(self, reason: str = "") -> None:
        """Stop answering (later calls get an error)."""
        self._shut_down = True

    unregister = shutdown

    def spin(self) -> None:
        """Block until the node shuts down (as ``rospy.spin``)."""
        from services.ros.rospy.client import spin

        spin()


class ServiceProxy:
    """Calls ``name``: ``proxy(*fields)``, ``proxy(**fields)`` or ``proxy(request)``."""

    def __init__(
        self, name: str, service_class: type[ServiceType], persistent: bool = False, headers: Any = None
    ) -> None:
        _check_service_class(service_class, "rospy.ServiceProxy")
        self.service_class = service_class
        self.request_class = service_class.Request
        self.response_class = service_class.Response
        self.resolved_name = process.names.resolve(name)
        self._name = name
        self._client: Client[Any] | None = None

    def __call__(self, *args: Any, **kwds: Any) -> Any:
        return self.call(*args, **kwds)

    def call(self, *args: Any, **kwds: Any) -> Any:
        """Send the request and return the response; ServiceException when there is none."""
        if len(args) == 1 and not kwds and isinstance(args[0], Message):
            request = args[0]
            if not isinstance(request, self.request_class):
                raise TypeError(
                    f"{self.resolved_name} takes {self.request_class.__name__}, got {type(request).__name__}"
                )
        else:
            request = self.request_class(*args, **kwds)
        try:
            return _blocking(self._runtime_client().call(request))
        except ServiceCallRejectedError as error:
            raise ServiceException(f"service [{self.resolved_name}] responded with an error: {_detail(error)}") from None
        except ServiceError as error:
            raise ServiceException(f"service [{self.resolved_name}] unavailable: {error}") from None

    def wait_for_service(self, timeout: float | DurationMsg | None = None) -> None:
        """Block until the service is served; ROSException after ``timeout``."""
        wait_for_service(self._name, timeout)

    def close(self) -> None:
        pass

    def _runtime_client(self) -> Client[Any]:
        if self._client is None:
            node = process.require_node("a service call")
            self._client = bridge.call(lambda: node.create_client(self.service_class, self._name))
        return self._client


def wait_for_service(service: str, timeout: float | DurationMsg | None = None) -> None:
    """Block until a node serves ``service``; ROSException after ``timeout`` (seconds or a
    Duration; None waits as long as it takes)."""
    node = process.require_node("rospy.wait_for_service")
    seconds = timeout.to_sec() if isinstance(timeout, DurationMsg) else timeout
    if seconds is not None and seconds <= 0:
        raise ValueError(f"timeout must be positive seconds, got {seconds}")
    client: Client[Any] = bridge.call(lambda: node.create_client(ServiceType, service))
    if not _blocking(client.wait_for_service(seconds)):
        raise ROSException(f"timeout exceeded while waiting for service {client.srv_name}")


def _blocking(coroutine: Any) -> Any:
    """Run ``coroutine`` on the bridge's loop and wait; a shutdown meanwhile is ROSInterruptException."""
    try:
        return bridge.run(coroutine)
    except concurrent.futures.CancelledError:
        if process.is_shutdown():
            raise ROSInterruptException("ROS shutdown request") from None
        raise


def _detail(error: ServiceCallRejectedError) -> str:
    """The handler's error as the node sent it (its JSON ``detail``), else the whole message."""
    text = str(error)
    _, _, body = text.partition(f"({error.status_code}): ")
    try:
        return str(json.loads(body)["detail"])
    except (ValueError, KeyError, TypeError):
        return text
