"""The rospy façade in this process against a real core (a subprocess), held to rospy's documented
behaviour: subscriber callbacks on threads of their own, Rate and sleep, services called with
positional or keyword fields or a request, handlers' return forms, ServiceException and
wait_for_service's ROSException, parameters (global, relative, ~private, ``_name:=value``),
%-formatted logging, shutdown hooks, timers, and a callback's exception shown at the user's line
while the node keeps running. Ctrl-C and SIGTERM on a ``skydeck run`` program are at the end."""

from __future__ import annotations

import logging
import signal
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.ros.conftest import until
from tests.web_ui.system import REPO, System

pytestmark = [pytest.mark.timeout(60)]


@pytest.fixture
def rospy(core: System, monkeypatch: pytest.MonkeyPatch) -> Iterator[object]:
    """The façade, with this process's rospy state fresh for each test (rospy has one node per
    process; tests make theirs with disable_signals=True, so pytest keeps its own handlers)."""
    from services.ros import rospy as facade
    from services.ros.rospy.core import process

    monkeypatch.setenv("SKYDECK_CORE_URL", core.url)
    process.__init__()  # type: ignore[misc]
    yield facade
    if facade.is_initialized() and not facade.is_shutdown():
        facade.signal_shutdown("test over")
    process.__init__()  # type: ignore[misc]


def _linked(publisher) -> None:  # type: ignore[no-untyped-def]
    until(lambda: publisher.get_num_connections() > 0, what=f"a subscriber of {publisher.resolved_name}")


def test_time_and_duration_are_genpys_and_compare_with_received_stamps(rospy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.builtin_interfaces import Time as StampMsg

    start = rospy.Time(5, 500)
    assert (start.secs, start.nsecs, start.to_sec()) == (5, 500, 5.0000005)
    later = start + rospy.Duration(1.5)
    assert isinstance(later, rospy.Time) and later - start == rospy.Duration(1.5)
    assert isinstance(later - start, rospy.Duration) and later - start > rospy.Duration(1)
    stamp = StampMsg(sec=6, nanosec=0)  # a header's stamp as received
    assert start < stamp and stamp > start and stamp - start == rospy.Duration(0, 999_999_500)
    assert isinstance(stamp - start, rospy.Duration)
    assert rospy.Time.from_sec(2.25) == StampMsg(sec=2, nanosec=250_000_000)
    assert rospy.Duration(2) * 3 == rospy.Duration(6) and rospy.Duration(3) / rospy.Duration(1.5) == 2.0
    with pytest.raises(TypeError):
        _ = start < rospy.Duration(1)  # a time is not a duration, as in ROS
    before = rospy.get_time()
    assert abs(rospy.Time.now().to_sec() - before) < 1.0  # wall time before init_node


def test_init_node_reads_ros1_arguments_and_private_parameters(rospy) -> None:  # type: ignore[no-untyped-def]
    argv = ["talker.py", "--fast", "chatter:=/news", "__ns:=/robot1", "_rate:=5", "_frame:=odom",
            "--ros-args", "-p", "ros2_style:=1"]  # fmt: skip
    with pytest.raises(ValueError, match="namespaces are not allowed"):
        rospy.init_node("a/b")
    rospy.init_node("talker", argv=argv, disable_signals=True)
    assert rospy.get_name() == "/robot1/talker" and rospy.get_namespace() == "/robot1/"
    assert rospy.resolve_name("chatter") == "/news" and rospy.resolve_name("~x") == "/robot1/talker/x"
    assert rospy.get_param("~rate") == 5 and rospy.get_param("/robot1/talker/frame") == "odom"
    assert rospy.myargv(argv) == ["talker.py", "--fast"]
    assert {"init_node", "Publisher", "ServiceProxy", "Rate"} <= set(rospy.__all__)
    rospy.init_node("talker", argv=argv, disable_signals=True)  # the same again: nothing happens
    with pytest.raises(rospy.ROSException, match="already been called with different arguments"):
        rospy.init_node("listener", disable_signals=True)


def test_anonymous_names_are_unique(rospy) -> None:  # type: ignore[no-untyped-def]
    rospy.init_node("listener", argv=[], anonymous=True, disable_signals=True)
    assert rospy.get_name().startswith("/listener_") and rospy.get_name() != "/listener"


def test_parameters_global_relative_private_search_and_delete(rospy) -> None:  # type: ignore[no-untyped-def]
    rospy.init_node("planner", argv=["x", "__ns:=/team"], disable_signals=True)
    rospy.set_param("/gains", {"p": 1.5, "d": [0.1, 0.2]})
    rospy.set_param("speed", 2)  # relative: /team/speed
    rospy.set_param("~mode", "fast")  # private: /team/planner/mode
    assert rospy.get_param("/team/speed") == 2 and rospy.get_param("/team/planner/mode") == "fast"
    assert rospy.get_param("/gains") == {"p": 1.5, "d": [0.1, 0.2]} and rospy.get_param("/gains/p") == 1.5
    assert rospy.get_param("~missing", 7) == 7
    with pytest.raises(KeyError):
        rospy.get_param("~missing")
    assert rospy.has_param("speed") and not rospy.has_param("/speed")
    assert rospy.search_param("mode") == "/team/planner/mode"
    assert rospy.search_param("gains/p") == "/gains/p" and rospy.search_param("nothing") is None
    assert {"/team/speed", "/team/planner/mode", "/gains/p", "/gains/d"} <= set(rospy.get_param_names())
    rospy.delete_param("speed")
    assert not rospy.has_param("speed")
    with pytest.raises(KeyError):
        rospy.delete_param("speed")


def test_subscribers_call_back_on_threads_of_their_own_while_main_loops(rospy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_msgs import Int32, String

    rospy.init_node("threads", argv=[], disable_signals=True)
    heard: dict[str, list[tuple[object, str]]] = {"a": [], "b": []}
    rospy.Subscriber("numbers", Int32, lambda m, key: heard[key].append((m.data, threading.current_thread().name)), "a")
    rospy.Subscriber("words", String, lambda m: heard["b"].append((m.data, threading.current_thread().name)))
    numbers = rospy.Publisher("numbers", Int32, queue_size=10)
    words = rospy.Publisher("words", String, queue_size=10)
    _linked(numbers)
    _linked(words)
    rate = rospy.Rate(100)
    started = time.monotonic()
    for i in range(20):  # a `while not rospy.is_shutdown()` main loop, publishing both ways rospy allows
        numbers.publish(Int32(i))
        words.publish(data=f"w{i}")
        rate.sleep()
    assert 0.15 < time.monotonic() - started < 1.0  # 20 passes at 100 Hz
    until(lambda: len(heard["a"]) == 20 and len(heard["b"]) == 20, what="40 messages")
    assert [n for n, _ in heard["a"]] == list(range(20))  # in order
    threads = {name for key in heard for _, name in heard[key]}
    assert len(threads) == 2 and threading.main_thread().name not in threads and "bridge" not in str(threads)
    with pytest.raises(TypeError, match="Expected std_msgs/msg/Int32"):
        numbers.publish(String("no"))


def test_a_slow_subscriber_keeps_the_newest_queue_size_messages(rospy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_msgs import Int32

    rospy.init_node("slow", argv=[], disable_signals=True)
    entered, gate = threading.Event(), threading.Event()
    slow_got: list[int] = []
    fast_got: list[int] = []

    def slow(msg) -> None:  # type: ignore[no-untyped-def]
        entered.set()
        gate.wait(10)
        slow_got.append(msg.data)

    rospy.Subscriber("burst", Int32, slow, queue_size=2)
    rospy.Subscriber("burst", Int32, lambda msg: fast_got.append(msg.data))  # queue_size=None: keeps all
    publisher = rospy.Publisher("burst", Int32, queue_size=100)
    _linked(publisher)
    publisher.publish(0)
    assert entered.wait(10)
    for i in range(1, 10):
        publisher.publish(i)
    until(lambda: len(fast_got) == 10, what="every message at the other subscriber")
    gate.set()
    until(lambda: len(slow_got) == 3, what="three callbacks")
    assert slow_got == [0, 8, 9] and fast_got == list(range(10))


def test_services_take_fields_in_order_keywords_or_a_request_and_answer_as_rospy(rospy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.ros_workshop import FlyCommand, FlyCommandRequest, FlyCommandResponse
    from shared_models.rosapi_msgs import TopicType
    from shared_models.std_srvs import Trigger, TriggerResponse

    rospy.init_node("server", argv=[], disable_signals=True)
    handled_on: list[str] = []

    def fly(request):  # type: ignore[no-untyped-def]
        handled_on.append(threading.current_thread().name)
        return FlyCommandResponse(True, f"to {request.x:g},{request.y:g}")

    rospy.Service("fly", FlyCommand, fly)
    rospy.Service("as_tuple", Trigger, lambda request: (True, "tuple"))
    rospy.Service("as_dict", Trigger, lambda request: {"success": True, "message": "dict"})
    rospy.Service("as_value", TopicType, lambda request: f"type of {request.topic}")
    rospy.Service("as_none", Trigger, lambda request: None)
    rospy.Service("as_response", Trigger, lambda request: TriggerResponse(message="object"))
    rospy.wait_for_service("fly", timeout=5)
    proxy = rospy.ServiceProxy("fly", FlyCommand)
    assert proxy(1.0, 2.0).message == "to 1,2"
    assert proxy(x=3.0, y=4.0).message == "to 3,4"
    assert proxy(FlyCommandRequest(5.0, 6.0)).message == "to 5,6"
    assert proxy.call(7.0, 8.0).success is True
    assert threading.main_thread().name not in handled_on
    assert rospy.ServiceProxy("as_tuple", Trigger)().message == "tuple"
    assert rospy.ServiceProxy("as_dict", Trigger)().message == "dict"
    assert rospy.ServiceProxy("as_value", TopicType)("/x").type == "type of /x"
    assert rospy.ServiceProxy("as_response", Trigger)().message == "object"
    with pytest.raises(rospy.ServiceException, match=r"service \[/as_none\] responded with an error: .*returned None"):
        rospy.ServiceProxy("as_none", Trigger)()
    with pytest.raises(TypeError):
        proxy(1.0, 2.0, 3.0)  # FlyCommand takes x and y


def test_blocking_service_calls_work_from_a_subscriber_callback(rospy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_msgs import Int32
    from shared_models.std_srvs import SetBool

    rospy.init_node("caller", argv=[], disable_signals=True)
    rospy.Service("double", SetBool, lambda request: (True, "yes" if request.data else "no"))
    answers: list[str] = []
    switch = rospy.ServiceProxy("double", SetBool)
    rospy.Subscriber("ask", Int32, lambda m: answers.append(switch(m.data > 0).message))
    publisher = rospy.Publisher("ask", Int32, queue_size=10)
    _linked(publisher)
    publisher.publish(1)
    publisher.publish(0)
    until(lambda: answers == ["yes", "no"], what="two answers from inside the callback")


def test_no_service_and_wait_timeouts_raise_rospys_exceptions(rospy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_srvs import Trigger

    rospy.init_node("lonely", argv=[], disable_signals=True)
    started = time.monotonic()
    with pytest.raises(rospy.ROSException, match="timeout exceeded while waiting for service /nobody"):
        rospy.wait_for_service("nobody", timeout=rospy.Duration(0.3))
    assert 0.25 < time.monotonic() - started < 3.0
    with pytest.raises(rospy.ServiceException, match=r"service \[/nobody\] unavailable"):
        rospy.ServiceProxy("/nobody", Trigger)()
    assert issubclass(rospy.ServiceException, rospy.ROSException)


def test_a_raising_callback_shows_the_users_line_and_the_node_keeps_running(rospy, caplog) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_msgs import Int32
    from shared_models.std_srvs import Trigger

    caplog.set_level(logging.INFO)
    rospy.init_node("buggy", argv=[], disable_signals=True)
    got: list[int] = []

    def callback(msg):  # type: ignore[no-untyped-def]
        if msg.data == 0:
            return [][msg.data]  # IndexError, on this line
        got.append(msg.data)

    rospy.Subscriber("ints", Int32, callback)
    rospy.Service("broken", Trigger, lambda request: 1 / 0)
    publisher = rospy.Publisher("ints", Int32, queue_size=10)
    _linked(publisher)
    for i in range(3):
        publisher.publish(i)
    until(lambda: got == [1, 2], what="the later messages")
    with pytest.raises(rospy.ServiceException, match="ZeroDivisionError"):
        rospy.ServiceProxy("broken", Trigger)()
    text = caplog.text
    assert "the subscriber callback of /ints raised (the node keeps running)" in text
    assert f'File "{__file__}", line' in text and "return [][msg.data]  # IndexError, on this line" in text
    assert "the service handler of /broken raised" in text and "ZeroDivisionError" in text
    assert f"{REPO}/services/" not in text


def test_logging_formats_as_rospy_and_filters_once_and_throttled(rospy, caplog) -> None:  # type: ignore[no-untyped-def]
    caplog.set_level(logging.DEBUG)
    rospy.loginfo("before init: %s", "printed")
    rospy.init_node("logger", argv=[], log_level=rospy.DEBUG, disable_signals=True)
    rospy.loginfo("got %d boxes at %.1f m", 3, 2.25)
    rospy.logwarn("plain %s text with no args")
    rospy.logdebug("debug %s", "shown")
    rospy.logerr("error %r", "x")
    rospy.logfatal("fatal")
    for i in range(3):
        rospy.loginfo_once("once %d", i)
        rospy.logwarn_throttle(60, "throttled %d", i)
    messages = [record.getMessage() for record in caplog.records]
    for line in ("before init: printed", "got 3 boxes at 2.2 m", "plain %s text with no args", "debug shown",
                 "error 'x'", "fatal", "once 0", "throttled 0"):  # fmt: skip
        assert line in messages, line
    assert "once 1" not in messages and "throttled 1" not in messages


def test_shutdown_runs_hooks_and_ends_sleeps_and_timers(rospy) -> None:  # type: ignore[no-untyped-def]
    rospy.init_node("stopper", argv=[], disable_signals=True)
    calls: list[str] = []
    rospy.on_shutdown(lambda: calls.append("plain"))
    rospy.on_shutdown(lambda reason: calls.append(f"reason={reason}"))
    ticks: list[object] = []
    rospy.Timer(rospy.Duration(0.05), ticks.append)
    once: list[object] = []
    rospy.Timer(rospy.Duration(0.05), once.append, oneshot=True)
    until(lambda: len(ticks) >= 3, what="three ticks")
    event = ticks[-1]
    assert event.current_real >= event.current_expected and event.last_real is not None  # type: ignore[attr-defined]
    assert len(once) == 1
    errors: list[BaseException] = []

    def sleeper() -> None:
        try:
            rospy.sleep(30)
        except rospy.ROSInterruptException as error:
            errors.append(error)

    thread = threading.Thread(target=sleeper)
    thread.start()
    rospy.signal_shutdown("done testing")
    thread.join(5)
    assert calls == ["plain", "reason=done testing"] and rospy.is_shutdown()
    assert len(errors) == 1 and isinstance(errors[0], KeyboardInterrupt)  # rospy's is one too
    with pytest.raises(rospy.ROSInterruptException):
        rospy.Rate(10).sleep()
    count = len(ticks)
    time.sleep(0.2)
    assert len(ticks) == count  # timers stopped
    late: list[str] = []
    rospy.on_shutdown(lambda: late.append("called at once"))
    assert late == ["called at once"]


def test_apis_rospy_has_and_skydeck_lacks_name_themselves(rospy) -> None:  # type: ignore[no-untyped-def]
    from services.ros.errors import NotProvidedError

    with pytest.raises(NotProvidedError, match="rospy.AnyMsg is a ROS API Skydeck does not provide"):
        _ = rospy.AnyMsg
    with pytest.raises(rospy.ROSInitException, match=r"call rospy.init_node\('name'\) first"):
        rospy.Publisher("x", object, queue_size=1)


_PROGRAM = """
import rospy
rospy.init_node("looper")
rospy.on_shutdown(lambda reason: print(f"hook: {reason}", flush=True))
rate = rospy.Rate(50)
print("looping", flush=True)
while not rospy.is_shutdown():
    rate.sleep()
"""


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_ctrl_c_and_sigterm_shut_a_main_loop_down_cleanly(core: System, tmp_path: Path, sig: signal.Signals) -> None:
    import os

    from services.launch.background import BackgroundProcess

    program = tmp_path / "looper.py"
    program.write_text(_PROGRAM)
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "run", str(program)],
        name="looper.py",
        cwd=REPO,
        env={**os.environ, "SKYDECK_CORE_URL": core.url, "PYTHONUNBUFFERED": "1"},
    )
    try:
        process.wait_for_line("looping", 30)
        process.popen.send_signal(sig)
        # One write for the hook's text: print("hook:", reason) writes its parts one by one, and
        # a log line from the node's own thread (its registration, late on a loaded machine) can
        # land between them, as it can under ROS.
        process.wait_for_line(f"hook: signal-{sig.name}", 10)
        assert process.popen.wait(10) in (0, 130)
    finally:
        process.stop(signal.SIGKILL, timeout_s=5)
    assert not any("Traceback" in line for line in process.lines), process.tail(20)
