"""The internal HTTP client against a real uvicorn server: keep-alive, replies of every shape,
and each way a request can fail."""

from __future__ import annotations

import asyncio
import datetime
import http.server
import ipaddress
import socket
import ssl
import threading
from collections.abc import AsyncIterator
from pathlib import Path

import pytest
import uvicorn
from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import NameOID
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse, Response, StreamingResponse
from starlette.routing import Route

from services.runtime.http_client import (
    MAX_REPLY_BYTES,
    HttpClient,
    HttpTimeout,
    HttpUnreachable,
    request_once,
)
from tests.conftest import free_port, held_again, held_socket, serve_on

pytestmark = pytest.mark.timeout(30)

_peers: set[tuple[str, int]] = set()  # client addresses seen: one per connection used


async def echo(request: Request) -> Response:
    _peers.add(request.client and (request.client.host, request.client.port))  # type: ignore[arg-type]
    return JSONResponse(
        {
            "method": request.method,
            "path": request.url.path,
            "query": request.url.query,
            "body": (await request.body()).decode(),
            "headers": {k: v for k, v in request.headers.items() if k in ("content-type", "authorization", "x-extra")},
        },
        status_code=int(request.query_params.get("status", "200")),
    )


async def slow(request: Request) -> Response:
    _peers.add(request.client and (request.client.host, request.client.port))  # type: ignore[arg-type]
    await asyncio.sleep(float(request.query_params["s"]))
    return JSONResponse({"slept": True})


async def chunked(request: Request) -> Response:
    async def parts() -> AsyncIterator[bytes]:
        for part in (b"one ", b"two ", b"three"):
            yield part

    return StreamingResponse(parts(), media_type="text/plain")


async def closing(request: Request) -> Response:
    return Response(b"bye", headers={"Connection": "close"})


async def huge(request: Request) -> Response:
    async def parts() -> AsyncIterator[bytes]:
        block = b"x" * (1024 * 1024)
        for _ in range(MAX_REPLY_BYTES // len(block) + 2):
            yield block

    return StreamingResponse(parts())


APP = Starlette(
    routes=[
        Route("/echo", echo, methods=["GET", "POST"]),
        Route("/slow", slow),
        Route("/chunked", chunked),
        Route("/close", closing),
        Route("/huge", huge),
    ]
)


@pytest.fixture
async def server() -> AsyncIterator[str]:
    sock = held_socket()
    port = sock.getsockname()[1]
    instance = uvicorn.Server(uvicorn.Config(APP, log_level="warning", lifespan="off"))
    task = await serve_on(instance, sock)
    _peers.clear()
    yield f"http://127.0.0.1:{port}"
    instance.should_exit = True
    await task


@pytest.fixture
async def client() -> AsyncIterator[HttpClient]:
    http = HttpClient(headers={"Authorization": "Bearer secret"})
    yield http
    await http.aclose()


async def test_post_sends_body_path_query_and_headers(server: str, client: HttpClient) -> None:
    reply = await client.post(f"{server}/echo?a=1", b'{"x": 1}', timeout_s=5, headers={"X-Extra": "yes"})
    assert reply.status == 200
    assert reply.headers["content-type"] == "application/json"
    assert reply.json() == {
        "method": "POST",
        "path": "/echo",
        "query": "a=1",
        "body": '{"x": 1}',
        "headers": {"content-type": "application/json", "authorization": "Bearer secret", "x-extra": "yes"},
    }


async def test_any_status_is_a_reply(server: str, client: HttpClient) -> None:
    reply = await client.get(f"{server}/echo?status=422", timeout_s=5)
    assert reply.status == 422
    assert reply.json()["method"] == "GET"


async def test_sequential_requests_share_one_connection(server: str, client: HttpClient) -> None:
    for _ in range(20):
        assert (await client.get(f"{server}/echo", timeout_s=5)).status == 200
    assert len(_peers) == 1


async def test_concurrent_requests_each_get_their_own_reply(server: str, client: HttpClient) -> None:
    replies = await asyncio.gather(*(client.post(f"{server}/echo", str(i), timeout_s=5) for i in range(30)))
    assert [reply.json()["body"] for reply in replies] == [str(i) for i in range(30)]


async def test_chunked_reply_is_joined(server: str, client: HttpClient) -> None:
    reply = await client.get(f"{server}/chunked", timeout_s=5)
    assert reply.body == b"one two three"


async def test_connection_close_reply_is_not_reused(server: str, client: HttpClient) -> None:
    assert (await client.get(f"{server}/close", timeout_s=5)).body == b"bye"
    assert (await client.get(f"{server}/echo", timeout_s=5)).status == 200
    assert (await client.get(f"{server}/close", timeout_s=5)).body == b"bye"


async def test_timeout_raises_and_the_client_keeps_working(server: str, client: HttpClient) -> None:
    with pytest.raises(HttpTimeout, match="within 0.2 s"):
        await client.get(f"{server}/slow?s=2", timeout_s=0.2)
    assert (await client.get(f"{server}/echo", timeout_s=5)).status == 200


async def test_nobody_listening_is_unreachable(client: HttpClient) -> None:
    with pytest.raises(HttpUnreachable, match="cannot connect"):
        await client.get(f"http://127.0.0.1:{free_port()}/echo", timeout_s=5)


async def test_a_reply_larger_than_the_limit_is_refused(server: str, client: HttpClient) -> None:
    with pytest.raises(HttpUnreachable, match="larger than"):
        await client.get(f"{server}/huge", timeout_s=20)


async def test_server_restart_between_calls_is_survived(client: HttpClient) -> None:
    """A kept-alive connection to a server that went away is replaced, not reported."""
    sock = held_socket()
    port = sock.getsockname()[1]
    for restart in (False, True):
        instance = uvicorn.Server(uvicorn.Config(APP, log_level="warning", lifespan="off"))
        task = await serve_on(instance, await held_again(port) if restart else sock)  # the same port again
        assert (await client.get(f"http://127.0.0.1:{port}/echo", timeout_s=5)).status == 200
        instance.should_exit = True
        await task


async def test_garbage_from_the_server_is_a_broken_connection(client: HttpClient) -> None:
    async def answer(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        await reader.readuntil(b"\r\n\r\n")
        writer.write(b"NOT HTTP AT ALL\r\n\r\n")
        await writer.drain()

    listener = await asyncio.start_server(answer, "127.0.0.1", 0, family=socket.AF_INET)
    port = listener.sockets[0].getsockname()[1]
    async with listener:
        with pytest.raises(HttpUnreachable, match="malformed reply"):
            await client.get(f"http://127.0.0.1:{port}/", timeout_s=5)


async def test_header_with_a_line_break_is_refused(server: str, client: HttpClient) -> None:
    with pytest.raises(ValueError, match="line break"):
        await client.post(f"{server}/echo", b"{}", timeout_s=5, headers={"Authorization": "Bearer x\r\nX-Evil: 1"})


async def test_only_http_and_https_urls(client: HttpClient) -> None:
    with pytest.raises(HttpUnreachable, match="http:// and https:// URLs only"):
        await client.get("ftp://example.org/", timeout_s=5)


async def test_kept_alive_connection_dropped_by_the_server_is_retried_once_on_a_new_one(client: HttpClient) -> None:
    """The race with a server's keep-alive timeout: it closes the idle connection just as the
    next request arrives, unanswered. The request goes again on a new connection."""
    requests_per_connection: list[int] = []

    async def answer_first_then_hang_up(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        requests_per_connection.append(0)
        while True:
            await reader.readuntil(b"\r\n\r\n")
            requests_per_connection[-1] += 1
            if requests_per_connection[-1] > 1:
                writer.close()
                return
            writer.write(b"HTTP/1.1 200 OK\r\nContent-Length: 2\r\n\r\nok")
            await writer.drain()

    listener = await asyncio.start_server(answer_first_then_hang_up, "127.0.0.1", 0, family=socket.AF_INET)
    url = f"http://127.0.0.1:{listener.sockets[0].getsockname()[1]}/"
    async with listener:
        assert (await client.get(url, timeout_s=5)).body == b"ok"
        assert (await client.get(url, timeout_s=5)).body == b"ok"
    assert requests_per_connection == [2, 1]


async def test_a_fresh_connection_that_breaks_is_not_retried(client: HttpClient) -> None:
    """Only a reused connection may have been dropped while idle; a new one that breaks means the
    server may have seen the request, so it is not sent twice."""
    seen = 0

    async def hang_up(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        nonlocal seen
        await reader.readuntil(b"\r\n\r\n")
        seen += 1
        writer.close()

    listener = await asyncio.start_server(hang_up, "127.0.0.1", 0, family=socket.AF_INET)
    async with listener:
        with pytest.raises(HttpUnreachable, match="closed the connection"):
            await client.post(f"http://127.0.0.1:{listener.sockets[0].getsockname()[1]}/", b"{}", timeout_s=5)
    assert seen == 1


async def test_a_short_timeout_after_a_long_one_on_the_same_connection_still_times_out(
    server: str, client: HttpClient
) -> None:
    """A connection keeps one timer across its requests: a later, earlier deadline must move it."""
    assert (await client.get(f"{server}/echo", timeout_s=30)).status == 200
    with pytest.raises(HttpTimeout, match="within 0.2 s"):
        await asyncio.wait_for(client.get(f"{server}/slow?s=3", timeout_s=0.2), 2)
    assert len(_peers) == 1  # both on the same kept-alive connection


async def test_a_long_timeout_after_a_short_one_is_not_cut_short(server: str, client: HttpClient) -> None:
    """The timer armed for the first request's deadline fires during the second: it waits on."""
    assert (await client.get(f"{server}/echo", timeout_s=0.2)).status == 200
    assert (await client.get(f"{server}/slow?s=0.5", timeout_s=5)).json() == {"slept": True}
    assert len(_peers) == 1


async def test_a_cancelled_request_spoils_its_connection_not_the_next_request(server: str, client: HttpClient) -> None:
    """The reply of a request given up on must not be read as the next one's."""
    task = asyncio.create_task(client.get(f"{server}/slow?s=0.3", timeout_s=5))
    await asyncio.sleep(0.1)
    task.cancel()
    with pytest.raises(asyncio.CancelledError):
        await task
    assert (await client.post(f"{server}/echo", b"next", timeout_s=5)).json()["body"] == "next"
    assert len(_peers) == 2  # the second on a new connection


async def test_start_hands_the_outcome_to_a_callback_once(server: str, client: HttpClient) -> None:
    """The callback form the core's gateway uses: a reply of any status, or the error, once."""
    outcomes: list[object] = []
    done = asyncio.Event()

    def on_done(outcome: object) -> None:
        outcomes.append(outcome)
        done.set()

    for url, timeout_s in ((f"{server}/echo?status=404", 5.0), (f"{server}/slow?s=2", 0.2)):
        done.clear()
        client.start("GET", url, timeout_s=timeout_s, on_done=on_done)
        await asyncio.wait_for(done.wait(), 5)
    await asyncio.sleep(0.3)  # nothing more comes for either
    assert [type(o).__name__ for o in outcomes] == ["HttpReply", "HttpTimeout"]
    assert outcomes[0].status == 404  # type: ignore[attr-defined]


async def test_a_fault_in_the_callback_is_logged_and_the_client_keeps_working(
    server: str, client: HttpClient, caplog: pytest.LogCaptureFixture
) -> None:
    called = asyncio.Event()

    def broken(outcome: object) -> None:
        called.set()
        raise RuntimeError("a bug in the caller")

    client.start("GET", f"{server}/echo", timeout_s=5, on_done=broken)
    await asyncio.wait_for(called.wait(), 5)
    assert "handling a reply of the HTTP client failed" in caplog.text
    assert (await client.get(f"{server}/echo", timeout_s=5)).status == 200


# -- https (a core behind a TLS proxy, as the CLI reaches it) ------------------------------------


def _certificate(folder: Path) -> tuple[Path, Path]:
    """A self-signed certificate for 127.0.0.1 and its key, as PEM files."""
    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "127.0.0.1")])
    now = datetime.datetime.now(datetime.UTC)
    certificate = (
        x509.CertificateBuilder()
        .subject_name(name)
        .issuer_name(name)
        .public_key(key.public_key())
        .serial_number(x509.random_serial_number())
        .not_valid_before(now - datetime.timedelta(minutes=5))
        .not_valid_after(now + datetime.timedelta(hours=1))
        .add_extension(x509.SubjectAlternativeName([x509.IPAddress(ipaddress.ip_address("127.0.0.1"))]), critical=False)
        .add_extension(x509.BasicConstraints(ca=True, path_length=None), critical=True)
        .sign(key, hashes.SHA256())
    )
    cert_file, key_file = folder / "cert.pem", folder / "key.pem"
    cert_file.write_bytes(certificate.public_bytes(serialization.Encoding.PEM))
    key_file.write_bytes(
        key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8, serialization.NoEncryption())
    )
    return cert_file, key_file


@pytest.fixture
async def tls_server(tmp_path: Path) -> AsyncIterator[tuple[str, Path]]:
    cert_file, key_file = _certificate(tmp_path)
    sock = held_socket()
    config = uvicorn.Config(APP, log_level="warning", lifespan="off", ssl_certfile=cert_file, ssl_keyfile=key_file)
    instance = uvicorn.Server(config)
    task = await serve_on(instance, sock)
    _peers.clear()
    yield f"https://127.0.0.1:{sock.getsockname()[1]}", cert_file
    instance.should_exit = True
    await task


async def test_https_to_a_trusted_server_keeps_its_connection(tls_server: tuple[str, Path]) -> None:
    url, cert_file = tls_server
    client = HttpClient(tls=ssl.create_default_context(cafile=cert_file))
    try:
        replies = [await client.post(f"{url}/echo?n={n}", b"{}", timeout_s=5) for n in range(3)]
    finally:
        await client.aclose()
    assert [reply.json()["query"] for reply in replies] == ["n=0", "n=1", "n=2"]
    assert len(_peers) == 1  # one TLS connection, kept alive


async def test_https_to_a_server_whose_certificate_is_not_trusted_is_unreachable(tls_server: tuple[str, Path]) -> None:
    url, _ = tls_server
    client = HttpClient()  # the system's certificates: a self-signed one is not among them
    try:
        with pytest.raises(HttpUnreachable, match="CERTIFICATE_VERIFY_FAILED"):
            await client.get(f"{url}/echo", timeout_s=5)
    finally:
        await client.aclose()


# -- one request from blocking code ---------------------------------------------------------------


async def test_request_once_from_a_thread(server: str) -> None:
    reply = await asyncio.to_thread(request_once, "POST", f"{server}/echo", b"{}", timeout_s=5, headers={"x-extra": "1"})
    assert reply.json()["headers"]["x-extra"] == "1"


class _Ok(http.server.BaseHTTPRequestHandler):
    def do_GET(self) -> None:  # noqa: N802 (http.server's name)
        self.send_response(200)
        self.send_header("Content-Length", "2")
        self.end_headers()
        self.wfile.write(b"ok")

    def log_message(self, *args: object) -> None:
        pass


async def test_request_once_from_blocking_code_in_a_coroutine() -> None:
    """A harness's poll called where a loop runs: the request takes a thread of its own (this
    loop waits, as for any blocking call; the server is elsewhere, here another thread)."""
    with http.server.ThreadingHTTPServer(("127.0.0.1", 0), _Ok) as other:
        thread = threading.Thread(target=other.serve_forever, daemon=True)
        thread.start()
        try:
            reply = request_once("GET", f"http://127.0.0.1:{other.server_address[1]}/", timeout_s=5)
        finally:
            other.shutdown()
    assert (reply.status, reply.body) == (200, b"ok")


def test_request_once_to_nobody_raises_unreachable() -> None:
    with pytest.raises(HttpUnreachable, match="cannot connect"):
        request_once("GET", f"http://127.0.0.1:{free_port()}/", timeout_s=5)
