#!/usr/bin/python3
"""Hostile input against netmc-server's console (--http): oversized and malformed requests, paths
that try to leave the fixed list of files, WebSocket frames over the limit, more connections than
the cap, and a fuzz pass of mutated requests. After each the console still answers. Also: a
WebSocket client that never reads while a job runs keeps the server's memory bounded.

Slow clients (64 /live readers that never read, 64 reconnecting slowloris senders) leave a page
its requests: 40 of 40 answered. Also: requests of another site's page (its Origin) and under another name (a foreign Host: DNS
rebinding) get 403, the token shown or not, on every route and on /live's upgrade.

Usage: console_hostile.py PORT SERVER_PID [--slow-reader-seconds S] [--token-file FILE]
Exit 0 when every check holds; 1 with the failed check named.
"""
import base64
import os
import random
import socket
import struct
import sys
import time

import websocket  # python3-websocket

HOST = "127.0.0.1"


def fail(what):
    print(f"FAIL: {what}")
    sys.exit(1)


def exchange(port, raw, timeout=5.0):
    """Sends raw bytes, returns what came back until the server closed or went quiet."""
    with socket.create_connection((HOST, port), timeout=timeout) as s:
        try:
            s.sendall(raw)
        except (BrokenPipeError, ConnectionResetError):
            pass
        data = b""
        try:
            while True:
                chunk = s.recv(65536)
                if not chunk:
                    break
                data += chunk
                if len(data) > 1 << 20:
                    break
        except (socket.timeout, ConnectionResetError):
            pass
        return data


def status_of(reply):
    if not reply.startswith(b"HTTP/1.1 "):
        return None
    return int(reply[9:12])


def get(port, path, extra=b""):
    return exchange(port, b"GET " + path + b" HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" + extra + b"\r\n")


def still_answers(port, after):
    reply = get(port, b"/metrics")
    if status_of(reply) != 200 or b"netmc_nodes_up" not in reply:
        fail(f"after {after} the console no longer answers /metrics: {reply[:200]!r}")


def rss_kib(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def main():
    port = int(sys.argv[1])
    pid = int(sys.argv[2])
    slow_seconds = 8.0
    token_file = sys.argv[sys.argv.index("--token-file") + 1] if "--token-file" in sys.argv else None
    if "--slow-reader-seconds" in sys.argv:
        slow_seconds = float(sys.argv[sys.argv.index("--slow-reader-seconds") + 1])

    # Oversized header and body, a malformed request, a query string.
    big_header = b"X-Pad: " + b"a" * 9000 + b"\r\n"
    if status_of(get(port, b"/metrics", big_header)) != 431:
        fail("a 9 KB header was not refused with 431")
    body = b"{" + b" " * 100_000 + b"}"
    reply = exchange(port, b"POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: " + str(len(body)).encode() +
                     b"\r\nConnection: close\r\n\r\n" + body)
    if status_of(reply) != 413:
        fail(f"a 100 KB body was not refused with 413: {reply[:100]!r}")
    if status_of(exchange(port, b"GARBAGE\r\n\r\n")) != 400:
        fail("a malformed request line was not refused with 400")
    if status_of(get(port, b"/api/state?x=1")) != 400:
        fail("a query string was not refused")
    print("oversized header 431, oversized body 413, malformed 400, query string 400")

    # Paths: only the fixed list exists; nothing names a file.
    for path in [b"/../../etc/passwd", b"/javascript/dygraphs/../../../../etc/passwd", b"/%2e%2e/%2e%2e/etc/passwd",
                 b"/javascript/dygraphs/dygraph.js", b"//etc/passwd", b"/console.js/../index.html",
                 b"/api/jobs/1/../../state", b"/api/jobs/-1", b"/api/jobs/99999999999999999999"]:
        reply = get(port, path)
        if status_of(reply) != 404 or b"root:" in reply:
            fail(f"{path!r} answered {reply[:80]!r}, not 404")
    print("9 paths outside the fixed list: 404, no file content")

    # Methods and the token.
    if status_of(exchange(port, b"DELETE /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")) != 405:
        fail("DELETE /api/state was not refused with 405")
    reply = exchange(port, b"POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 20\r\nConnection: close\r\n\r\n"
                           b"{\"preset\":\"seed001\"}")
    if status_of(reply) != 401:
        fail(f"a job started without the token was not refused with 401: {reply[:120]!r}")
    reply = exchange(port, b"POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer wrong-token-wrong-token\r\n"
                           b"Content-Length: 20\r\nConnection: close\r\n\r\n{\"preset\":\"seed001\"}")
    if status_of(reply) != 401:
        fail("a job started with a wrong token was not refused with 401")
    print("DELETE 405; start without a token 401, with a wrong token 401")

    # Another site's page, or this console under another name: 403 whatever the request carries.
    token = open(token_file).read().strip() if token_file else "no-token-given"
    job = b"{\"preset\":\"seed001\"}"
    cross_site = [
        (b"POST /api/jobs", b"Host: 127.0.0.1:" + str(port).encode() + b"\r\nOrigin: http://evil.example\r\n"
         b"Content-Type: text/plain\r\nAuthorization: Bearer " + token.encode() + b"\r\n", job),
        (b"POST /api/jobs/1/cancel", b"Host: 127.0.0.1\r\nOrigin: null\r\nAuthorization: Bearer " + token.encode() +
         b"\r\n", b"{}"),
        (b"GET /api/state", b"Host: evil.example:" + str(port).encode() + b"\r\n", b""),
        (b"GET /metrics", b"Host: evil.example\r\n", b""),
        (b"GET /", b"Host: rebound.evil.example\r\n", b""),
        (b"GET /api/state", b"", b""),  # no Host at all
        (b"GET /live", b"Host: 127.0.0.1\r\nOrigin: http://evil.example\r\nUpgrade: websocket\r\n"
         b"Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n", b""),
    ]
    for line, headers, body in cross_site:
        raw = line + b" HTTP/1.1\r\n" + headers + b"Content-Length: " + str(len(body)).encode() + \
            b"\r\nConnection: close\r\n\r\n" + body
        reply = exchange(port, raw)
        if status_of(reply) != 403:
            fail(f"{line.decode()} with {headers.decode().strip()!r} answered {reply[:120]!r}, not 403")
    with_origin = exchange(port, b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\nOrigin: http://127.0.0.1:" +
                           str(port).encode() + b"\r\nConnection: close\r\n\r\n")
    if status_of(with_origin) != 200:
        fail(f"the console's own page (Origin http://127.0.0.1:{port}) was refused: {with_origin[:120]!r}")
    print(f"{len(cross_site)} cross-site or foreign-Host requests (token {'shown' if token_file else 'none'}): 403; "
          "the console's own origin: 200")

    # WebSocket: the hello, then a frame over 1 KiB closes the connection.
    ws = websocket.create_connection(f"ws://{HOST}:{port}/live", timeout=5)
    hello = ws.recv()
    if '"type":"hello"' not in hello:
        fail(f"/live's first message is not the hello: {hello[:100]}")
    ws.send("x" * 100)  # small: ignored
    ws.send("x" * 5000)
    closed = False
    deadline = time.time() + 5
    while time.time() < deadline:
        try:
            frame = ws.recv()
            if frame == "" or frame is None:
                closed = True
                break
        except (websocket.WebSocketConnectionClosedException, ConnectionResetError, OSError):
            closed = True
            break
    if not closed:
        fail("a 5000-byte WebSocket frame did not close the connection")
    if status_of(exchange(port, b"GET /other HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                                b"Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n")) != 404:
        fail("a WebSocket upgrade outside /live was not refused")
    print("/live: hello first; a 5000-byte frame closed the connection; upgrades elsewhere 404")

    # More connections than the cap, none sending a request: the longest-waiting ones make room.
    held = []
    for _ in range(80):
        try:
            held.append(socket.create_connection((HOST, port), timeout=2))
        except OSError:
            break
    time.sleep(0.5)
    closed = []  # looked at all at once, well within the 10 s a request may take to arrive
    for i, s in enumerate(held):
        s.setblocking(False)
        try:
            if s.recv(1) == b"":
                closed.append(i)
        except ConnectionResetError:
            closed.append(i)
        except BlockingIOError:
            pass
    for s in held:
        s.close()
    over = len(held) - 64
    if not over - 1 <= len(closed) <= over + 1 or (closed and max(closed) >= len(held) - over):
        fail(f"of {len(held)} idle connections, these were closed: {closed} (expected the {over} oldest)")
    time.sleep(0.5)
    still_answers(port, "80 connections at once")
    print(f"80 idle connections: the {len(closed)} oldest closed to make room (cap 64); the console answers after")

    # Slow clients cannot lock a browser out: 64 /live readers that never read, then 64 slowloris
    # senders that reconnect as soon as they are closed; meanwhile 40 requests of a page.
    def page_requests(count):
        ok = 0
        for _ in range(count):
            try:
                reply = exchange(port, b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n",
                                 timeout=3.0)
                ok += status_of(reply) == 200 and reply.rstrip().endswith(b"}")
            except OSError:
                pass
            time.sleep(0.02)
        return ok

    readers, statuses = [], {}
    for _ in range(64):
        r = socket.create_connection((HOST, port), timeout=3)
        r.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        r.sendall(b"GET /live HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                  b"Sec-WebSocket-Key: " + base64.b64encode(os.urandom(16)) + b"\r\nSec-WebSocket-Version: 13\r\n\r\n")
        code = status_of(r.recv(12))
        statuses[code] = statuses.get(code, 0) + 1
        readers.append(r)
    ok = page_requests(40)
    for r in readers:
        r.close()
    if ok != 40:
        fail(f"with 64 /live readers that never read ({statuses}), /api/state answered {ok} of 40")
    print(f"64 /live readers that never read (upgrade answers {statuses}): /api/state 40 of 40")

    import threading
    stop = threading.Event()
    def slowloris():
        while not stop.is_set():
            try:
                s = socket.create_connection((HOST, port), timeout=2)
                s.sendall(b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\n")
                while not stop.is_set():  # a header line every 0.5 s, never the end of the request
                    time.sleep(0.5)
                    s.sendall(b"X-Slow: 1\r\n")
            except OSError:
                pass
    threads = [threading.Thread(target=slowloris, daemon=True) for _ in range(64)]
    for t in threads:
        t.start()
    time.sleep(1.0)
    ok = page_requests(40)
    stop.set()
    for t in threads:
        t.join(timeout=5)
    if ok != 40:
        fail(f"with 64 reconnecting slowloris senders, /api/state answered {ok} of 40")
    print("64 reconnecting slowloris senders: /api/state 40 of 40")
    time.sleep(0.5)
    still_answers(port, "slow clients")

    # Fuzz: mutated requests, each on a connection of its own; nothing crashes the server.
    rng = random.Random(20261126)
    # Connection: close, so that a request the server answers is not then waited on for 0.5 s.
    seeds = [b"GET /metrics HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n",
             b"POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Length: 20\r\n\r\n"
             b"{\"preset\":\"seed001\"}",
             b"GET /live HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
             b"Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n",
             b"GET /api/jobs/1 HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nTransfer-Encoding: chunked\r\n\r\n"
             b"5\r\nhello\r\n0\r\n\r\n"]
    answered = 0
    for i in range(600):
        raw = bytearray(rng.choice(seeds))
        for _ in range(rng.randint(1, 8)):
            op = rng.randrange(4)
            at = rng.randrange(len(raw) + 1)
            if op == 0 and raw:
                raw[min(at, len(raw) - 1)] = rng.randrange(256)
            elif op == 1:
                raw[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 40)))
            elif op == 2 and raw:
                del raw[at:at + rng.randint(1, 20)]
            else:
                raw[at:at] = rng.choice([b"\r\n", b"Content-Length: 99999999999\r\n", b"\x00", b"%00", b"../",
                                         b"Transfer-Encoding: chunked\r\n", b":" * 300])
        reply = exchange(port, bytes(raw) + b"\r\n\r\n", timeout=0.5)
        if reply.startswith(b"HTTP/1.1 "):
            answered += 1
        if i % 100 == 99:
            still_answers(port, f"{i + 1} mutated requests")
    still_answers(port, "600 mutated requests")
    print(f"fuzz: 600 mutated requests ({answered} answered with a status line), the server still answers")

    # A WebSocket client that never reads: the server's memory stays bounded while the feed runs.
    key = base64.b64encode(os.urandom(16))
    stuck = socket.create_connection((HOST, port))
    stuck.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    stuck.sendall(b"GET /live HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Key: " +
                  key + b"\r\nSec-WebSocket-Version: 13\r\n\r\n")
    start_rss = rss_kib(pid)
    samples = []
    end = time.time() + slow_seconds
    while time.time() < end:
        time.sleep(0.5)
        samples.append(rss_kib(pid))
    # Its leaving, in the order that once crashed the server: the read side ends (FIN) while a
    # write to it is still pending, then the connection is reset under that write.
    stuck.shutdown(socket.SHUT_WR)
    time.sleep(0.5)
    stuck.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
    stuck.close()
    time.sleep(0.5)
    if not os.path.exists(f"/proc/{pid}") or "zombie" in open(f"/proc/{pid}/status").read():
        fail("the server died when a WebSocket reader left in the middle of a write")
    grown = max(samples) - start_rss
    print(f"a WebSocket reader that never read for {slow_seconds:.0f} s: server RSS {start_rss} -> max {max(samples)} KiB "
          f"(+{grown} KiB)")
    if grown > 64 * 1024:
        fail(f"the server grew by {grown} KiB with a reader that never reads")
    still_answers(port, "a reader that never read")
    print("console hostile checks: all passed")


if __name__ == "__main__":
    main()
