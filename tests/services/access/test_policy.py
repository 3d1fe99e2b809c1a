"""The one policy: every subject x verb x name decision, the refusals' statuses and lines, what a
service call is, a class's rules file, and the fences a core loads (docs/security.md)."""

from __future__ import annotations

import inspect
from pathlib import Path

import pytest

from services.access import (
    ClassRules,
    ClassTokensError,
    Fences,
    Forbidden,
    Policy,
    RateLimits,
    TokenNeeded,
    TokenSet,
    Verb,
    make_class_tokens,
    service_verb,
    write_tokens,
)
from services.access.policy import KILL_NODE_SERVICE, WORLD_RESET_SERVICES, name_matches

pytestmark = pytest.mark.timeout(30)

TOKENS = make_class_tokens(["alice", "bob"])
PROCESS = "the-process-token-of-this-core"


def _class(rules: ClassRules | None = None) -> Policy:
    return Policy(tokens=TokenSet(TOKENS), process_token=PROCESS, rules=rules)


# What alice (a student) may and may not do, verb by verb, with the default rules.
ALICE = {
    Verb.READ: (["/alice/scan", "/alice", "/clock", "/tf", "/tf_static", "/simulator/world"], ["/bob/scan", "/rosout", "/alicex/scan"]),
    Verb.PUBLISH: (["/alice/cmd_vel", "/rosout", "/parameter_events"], ["/bob/cmd_vel", "/clock", "/cmd_vel"]),
    Verb.CALL: (["/alice/wall_follower/get_parameters", "/rosapi/topics"], ["/bob/x", "/control/take_off"]),
    Verb.SERVE: (["/alice/srv"], ["/bob/srv", "/rosapi/mine"]),
    Verb.REGISTER: (["/alice/wall_follower", "/alice"], ["/bob/wall_follower", "/wall_follower", "/alicex"]),
    Verb.SET_PARAMETER: (["/alice/wall_follower"], ["/bob/wall_follower", "/sim"]),
    Verb.KILL_NODE: (["/alice/wall_follower"], ["/bob/wall_follower", "/sim", ""]),
    Verb.RESET_WORLD: ([], ["/simulator/reset"]),
    Verb.RECORD: (["/alice/scan", "/clock"], ["/bob/scan", "/**"]),
    Verb.CONFIGURE: ([], ["/"]),
}


@pytest.mark.parametrize(("verb", "name"), [(v, n) for v, (ok, _) in ALICE.items() for n in ok])
def test_a_student_may_act_in_their_namespace_and_on_what_is_shared(verb: Verb, name: str) -> None:
    policy = _class()
    assert policy.refusal(policy.subject(TOKENS["alice"]), verb, name) is None


@pytest.mark.parametrize(("verb", "name"), [(v, n) for v, (_, refused) in ALICE.items() for n in refused])
def test_a_student_is_refused_elsewhere_with_403_and_one_line(verb: Verb, name: str) -> None:
    policy = _class()
    refusal = policy.refusal(policy.subject(TOKENS["alice"]), verb, name)
    assert isinstance(refusal, Forbidden) and refusal.http_status == 403 and refusal.close_code == 1008
    text = str(refusal)
    assert "\n" not in text and ("alice" in text or "instructor" in text)


def test_the_refusals_say_what_is_allowed() -> None:
    policy = _class()
    alice = policy.subject(TOKENS["alice"])
    assert str(policy.refusal(alice, Verb.PUBLISH, "/bob/cmd_vel")) == (
        "alice may not publish on /bob/cmd_vel: only under /alice and the class's shared /rosout, /parameter_events"
    )
    assert str(policy.refusal(alice, Verb.REGISTER, "/bob/x")) == "alice may not run a node named /bob/x: only under /alice"
    assert "only the instructor may reset the world" in str(policy.refusal(alice, Verb.RESET_WORLD, "/simulator/reset"))
    assert "only the instructor may change the class" in str(policy.refusal(alice, Verb.CONFIGURE, "/"))


@pytest.mark.parametrize("who", ["instructor", "process"])
@pytest.mark.parametrize("verb", list(Verb))
def test_the_instructor_and_the_process_token_may_do_everything(who: str, verb: Verb) -> None:
    policy = _class()
    token = TOKENS["instructor"] if who == "instructor" else PROCESS
    for name in ("/bob/scan", "/alice/x", "/simulator/reset", "/"):
        assert policy.refusal(policy.subject(token), verb, name) is None


@pytest.mark.parametrize("verb", list(Verb))
def test_in_a_class_no_token_opens_nothing_and_says_to_present_one(verb: Verb) -> None:
    policy = _class()
    for token in ("", "a token nobody has"):
        refusal = policy.refusal(policy.subject(token), verb, "/clock")
        assert isinstance(refusal, TokenNeeded) and refusal.http_status == 401
        assert "this core runs a class" in str(refusal) and "token" in str(refusal)


@pytest.mark.parametrize("verb", list(Verb))
def test_without_a_class_the_process_token_guards_all_but_reading(verb: Verb) -> None:
    policy = Policy(process_token=PROCESS)
    refusal = policy.refusal(policy.subject(""), verb, "/drone/cmd_vel")
    if verb is Verb.READ:
        assert refusal is None
    else:
        assert isinstance(refusal, TokenNeeded) and "need the token" in str(refusal)
    assert policy.refusal(policy.subject(PROCESS), verb, "/drone/cmd_vel") is None


@pytest.mark.parametrize("verb", list(Verb))
def test_with_no_class_and_no_token_everyone_may_do_everything(verb: Verb) -> None:
    policy = Policy()
    assert policy.open and policy.refusal(policy.subject(""), verb, "/anything") is None


def test_the_rules_share_more_and_grant_reading_to_some() -> None:
    rules = ClassRules.model_validate({"shared": {"read": ["/simulator/**"], "call": []}, "reads": {"alice": ["/bob/**"]}})
    policy = _class(rules)
    alice, bob = policy.subject(TOKENS["alice"]), policy.subject(TOKENS["bob"])
    assert policy.refusal(alice, Verb.READ, "/bob/scan") is None
    assert policy.refusal(bob, Verb.READ, "/alice/scan") is not None
    assert policy.refusal(bob, Verb.READ, "/simulator/robots") is None
    assert policy.refusal(bob, Verb.READ, "/clock") is not None  # the shared list replaced the default
    assert policy.refusal(bob, Verb.CALL, "/rosapi/topics") is not None
    assert policy.refusal(alice, Verb.PUBLISH, "/bob/cmd_vel") is not None  # reading is all it grants


def test_name_patterns() -> None:
    assert name_matches("/bob/**", "/bob") and name_matches("/bob/**", "/bob/scan") and not name_matches("/bob/**", "/bobby")
    assert name_matches("/**", "/x") and name_matches("/clock", "/clock") and not name_matches("/clock", "/clock/x")
    for bad in ("clock", "/a b", "/bob/*", "/**/x"):
        with pytest.raises(ValueError):
            ClassRules.model_validate({"shared": {"read": [bad]}})


def test_what_a_service_call_is() -> None:
    assert service_verb(KILL_NODE_SERVICE, b'{"node": "/bob/wall_follower"}') == (Verb.KILL_NODE, "/bob/wall_follower")
    assert service_verb(KILL_NODE_SERVICE, b'{"node": "alice/x/"}') == (Verb.KILL_NODE, "/alice/x")
    for body in (b"", b"{", b"[]", b'{"node": 3}'):
        assert service_verb(KILL_NODE_SERVICE, body) == (Verb.KILL_NODE, "")
    assert service_verb("/simulator/reset", b"") == (Verb.RESET_WORLD, "/simulator/reset")
    assert service_verb("/bob/node/set_parameters", b"{}") == (Verb.SET_PARAMETER, "/bob/node")
    assert service_verb("/bob/node/set_parameters_atomically", b"") == (Verb.SET_PARAMETER, "/bob/node")
    assert service_verb("/bob/node/get_parameters", b"") == (Verb.CALL, "/bob/node/get_parameters")


def test_the_policy_names_the_services_the_launch_and_the_simulator_serve() -> None:
    import sim_server.world_node
    from services.launch.control import KILL_SERVICE

    assert KILL_SERVICE == KILL_NODE_SERVICE
    source = inspect.getsource(sim_server.world_node)
    assert all(f'"{name}"' in source for name in WORLD_RESET_SERVICES)


def test_describe_says_who_and_what() -> None:
    policy = _class()
    alice = policy.describe(policy.subject(TOKENS["alice"]))
    assert alice["subject"] == "alice" and alice["role"] == "student" and alice["namespace"] == "/alice"
    assert alice["may"]["publish"] == ["/alice/**", "/rosout", "/parameter_events"]  # type: ignore[index]
    assert alice["may"]["reset_world"] == []  # type: ignore[index]
    assert policy.describe(policy.subject(TOKENS["instructor"]))["may"]["configure"] == ["/**"]  # type: ignore[index]
    nobody = Policy(process_token=PROCESS).describe(Policy(process_token=PROCESS).subject(""))
    assert nobody["may"]["read"] == ["/**"] and nobody["may"]["publish"] == []  # type: ignore[index]


LIMITS = RateLimits(messages_per_s=10, bytes_per_s=1000, calls_in_flight=2)


def _tokens_file(tmp_path: Path) -> Path:
    path = tmp_path / "class-tokens.csv"
    write_tokens(path, TOKENS)
    return path


def test_fences_load_a_class_and_its_rules(tmp_path: Path) -> None:
    rules = tmp_path / "rules.yaml"
    rules.write_text("reads:\n  alice: [/bob/**]\n")
    fences = Fences.load(tokens_file=_tokens_file(tmp_path), rules_file=rules, process_token="", limits=LIMITS)
    alice = fences.admit(TOKENS["alice"])
    assert fences.in_class and alice.subject.name == "alice" and alice.allows(Verb.READ, "/bob/scan")
    assert alice.bucket is not None and fences.admit(TOKENS["instructor"]).bucket is None


@pytest.mark.parametrize(
    ("rules_text", "process_token", "said"),
    [
        ("reads:\n  carol: [/bob/**]\n", "", "reads names carol, who have no token"),
        ("shared:\n  read: [clock]\n", "", "rules.yaml: shared.read.0: Value error"),
        ("sharing: {}\n", "", "rules.yaml: sharing: Extra inputs"),
        ("shared: [\n", "", "cannot read"),
        (None, TOKENS["bob"], "SKYDECK_TOKEN is bob's class token"),
    ],
)
def test_fences_refuse_what_cannot_be_used_in_one_line(
    tmp_path: Path, rules_text: str | None, process_token: str, said: str
) -> None:
    rules = None
    if rules_text is not None:
        rules = tmp_path / "rules.yaml"
        rules.write_text(rules_text)
    with pytest.raises(ClassTokensError) as refused:
        Fences.load(tokens_file=_tokens_file(tmp_path), rules_file=rules, process_token=process_token, limits=LIMITS)
    assert said in str(refused.value) and "\n" not in str(refused.value)


def test_rules_without_a_class_are_refused(tmp_path: Path) -> None:
    with pytest.raises(ClassTokensError, match="need the class's tokens"):
        Fences.load(tokens_file=None, rules_file=tmp_path / "r.yaml", process_token="", limits=LIMITS)


def test_a_pass_decides_each_name_once(monkeypatch: pytest.MonkeyPatch) -> None:
    fences = Fences(_class(), LIMITS)
    alice = fences.admit(TOKENS["alice"])
    asked: list[str] = []
    decide = fences.policy.refusal
    monkeypatch.setattr(fences.policy, "refusal", lambda *args: asked.append(args[2]) or decide(*args))
    for _ in range(100):
        alice.allows(Verb.READ, "/alice/scan")
        with pytest.raises(Forbidden):
            alice.check(Verb.READ, "/bob/scan")
    assert asked == ["/alice/scan", "/bob/scan"]
