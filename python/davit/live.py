"""`python3 -m davit.live DECK [--port P] [--speed K]`: a launch paced to the wall clock
(K x real time), its state served at 30 Hz over a WebSocket on loopback, and a browser page
(python/davit/live_page/index.html, plain WebGL) that shows it and takes a trainee's
controls. Standard library only (RFC 6455 by hand); the run is the library's (davit.Launch).

Client -> server messages are JSON objects: {"cmd": "lower"}, {"cmd": "stop"},
{"cmd": "speed", "value": drum m/s}, {"cmd": "estop"}, {"cmd": "release"}. Anything else
(bad JSON, unknown commands, values out of range, binary or oversized frames) is counted
and ignored: it never stops the run. Server -> client: one JSON state per frame.
"""
import argparse
import base64
import hashlib
import json
import math
import pathlib
import socket
import struct
import threading
import time

import davit

GUID = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11"  # RFC 6455, section 1.3
PAGE = pathlib.Path(__file__).resolve().parent / "live_page" / "index.html"
FRAME_HZ = 30.0
MAX_MESSAGE = 4096


def accept_key(key):
    return base64.b64encode(hashlib.sha1((key + GUID).encode()).digest()).decode()


def encode_frame(text):
    """A server's unmasked text frame."""
    data = text.encode()
    n = len(data)
    if n < 126:
        head = struct.pack("!BB", 0x81, n)
    elif n < 65536:
        head = struct.pack("!BBH", 0x81, 126, n)
    else:
        head = struct.pack("!BBQ", 0x81, 127, n)
    return head + data


def read_exact(sock, n):
    buf = b""
    while len(buf) < n:
        chunk = sock.recv(n - len(buf))
        if not chunk:
            raise ConnectionError("closed")
        buf += chunk
    return buf


def read_frame(sock):
    """(opcode, payload) of the next client frame; ValueError for one over MAX_MESSAGE."""
    b0, b1 = read_exact(sock, 2)
    opcode, masked, n = b0 & 0x0F, b1 & 0x80, b1 & 0x7F
    if n == 126:
        n = struct.unpack("!H", read_exact(sock, 2))[0]
    elif n == 127:
        n = struct.unpack("!Q", read_exact(sock, 8))[0]
    if n > MAX_MESSAGE:
        raise ValueError("frame too long")
    mask = read_exact(sock, 4) if masked else b"\0\0\0\0"
    payload = bytes(c ^ mask[i % 4] for i, c in enumerate(read_exact(sock, n)))
    return opcode, payload


class LiveServer:
    """The paced run and its clients."""

    def __init__(self, deck, port=8765, speed=1.0, host="127.0.0.1"):
        self.run = davit.Launch.from_file(deck)
        self.deck = deck
        self.speed = speed
        self.lock = threading.Lock()
        self.clients = []
        self.commands = []
        self.stats = {"frames": 0, "deadline_misses": 0, "worst_step_s": 0.0,
                      "bad_messages": 0, "clients": 0}
        self.error = None
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.sock.bind((host, port))
        self.sock.listen(16)
        self.port = self.sock.getsockname()[1]
        self.stopping = False
        self.exit_at_end = False

    # ---- network
    def serve(self):
        threading.Thread(target=self.accept_loop, daemon=True).start()
        self.pace_loop()

    def accept_loop(self):
        while not self.stopping:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            threading.Thread(target=self.handle, args=(conn,), daemon=True).start()

    def handle(self, conn):
        try:
            conn.settimeout(30.0)
            request = b""
            while b"\r\n\r\n" not in request:
                chunk = conn.recv(4096)
                if not chunk or len(request) > 16384:
                    conn.close()
                    return
                request += chunk
            lines = request.split(b"\r\n")
            path = lines[0].split(b" ")[1].decode(errors="replace") if b" " in lines[0] else "/"
            headers = {}
            for line in lines[1:]:
                if b":" in line:
                    k, v = line.split(b":", 1)
                    headers[k.strip().lower().decode(errors="replace")] = v.strip().decode(
                        errors="replace")
            if headers.get("upgrade", "").lower() == "websocket" and "sec-websocket-key" in headers:
                self.websocket(conn, headers["sec-websocket-key"])
            else:
                self.http(conn, path)
        except (OSError, ConnectionError, ValueError, IndexError):
            pass
        finally:
            try:
                conn.close()
            except OSError:
                pass

    def http(self, conn, path):
        if path in ("/", "/index.html"):
            body, status, kind = PAGE.read_bytes(), "200 OK", "text/html; charset=utf-8"
        else:
            body, status, kind = b"not found", "404 Not Found", "text/plain"
        conn.sendall(f"HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: "
                     f"{len(body)}\r\nConnection: close\r\n\r\n".encode() + body)

    def websocket(self, conn, key):
        conn.sendall(("HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\n"
                      "Connection: Upgrade\r\nSec-WebSocket-Accept: "
                      f"{accept_key(key)}\r\n\r\n").encode())
        conn.settimeout(None)
        with self.lock:
            self.clients.append(conn)
            self.stats["clients"] += 1
        try:
            while True:
                try:
                    opcode, payload = read_frame(conn)
                except ValueError:
                    self.bad_message()
                    return
                if opcode == 0x8:
                    return
                if opcode == 0x1:
                    self.message(payload)
                elif opcode not in (0x9, 0xA):
                    self.bad_message()
        finally:
            with self.lock:
                if conn in self.clients:
                    self.clients.remove(conn)

    def bad_message(self):
        with self.lock:
            self.stats["bad_messages"] += 1

    def message(self, payload):
        try:
            msg = json.loads(payload.decode())
            cmd = msg["cmd"]
            if cmd not in ("lower", "stop", "speed", "estop", "release"):
                raise ValueError(cmd)
            value = float(msg.get("value", 0.0)) if cmd == "speed" else 0.0
            if not (math.isfinite(value) and 0.0 <= value <= 2.0):
                raise ValueError(value)
        except (ValueError, KeyError, TypeError, UnicodeDecodeError, AttributeError):
            self.bad_message()
            return
        with self.lock:
            self.commands.append((cmd, value))

    # ---- the paced run
    def apply(self, cmd, value):
        run = self.run
        try:
            if cmd == "lower":
                run.set_winch_speed(self.drum, ramp=1.0)
            elif cmd == "stop":
                run.brake(1.0)
            elif cmd == "speed":
                self.drum = value
                run.set_winch_speed(value, ramp=1.0)
            elif cmd == "estop":
                run.brake(0.05)
            elif cmd == "release":
                run.release()
        except davit.DavitError:
            self.bad_message()

    def state(self, wall):
        run = self.run
        pose = run.boat_pose()
        ship = run.ship_pose()
        ev = run.events()
        checks = {k: [None if math.isnan(x) else x for x in v]
                  for k, v in run.rule_checks().items()} if self.stats["frames"] % 30 == 0 else None
        out = {"t": run.time, "wall": wall, "boat": list(pose["position"]),
               "euler": list(pose["euler"]), "velocity": list(pose["velocity"]),
               "ship": list(ship["position"]) + list(ship["euler"]),
               "hooks": run.hooks().tolist(), "blocks": run.blocks().tolist(),
               "slings": list(run.sling_tensions()), "falls": list(run.fall_tensions()),
               "fenders": list(run.fender_forces()),
               "events": {k: ev[k] for k in ("first_contact", "waterborne", "release")},
               "impacts": len(ev["impacts"]), "finished": run.finished,
               "stats": dict(self.stats), "error": self.error}
        if checks is not None:
            out["checks"] = checks
        return json.dumps(out)

    def pace_loop(self, max_wall=None):
        """Advance the run to speed x wall time, one frame every 1/30 s, until it ends."""
        self.drum = 0.7
        period = 1.0 / FRAME_HZ
        start = time.perf_counter()
        k = 0
        while not self.stopping:
            k += 1
            with self.lock:
                commands, self.commands = self.commands, []
            for cmd, value in commands:
                self.apply(cmd, value)
            target = k * period * self.speed
            t0 = time.perf_counter()
            if not self.run.finished and self.error is None:
                try:
                    self.run.advance_to(target)
                except davit.DavitError as err:
                    self.error = err.message
            step = time.perf_counter() - t0
            self.stats["worst_step_s"] = max(self.stats["worst_step_s"], step)
            text = encode_frame(self.state(time.perf_counter() - start))
            with self.lock:
                clients = list(self.clients)
            for c in clients:
                try:
                    c.sendall(text)
                except OSError:
                    with self.lock:
                        if c in self.clients:
                            self.clients.remove(c)
            self.stats["frames"] += 1
            delay = start + k * period - time.perf_counter()
            if delay < 0:
                self.stats["deadline_misses"] += 1
            else:
                time.sleep(delay)
            if max_wall is not None and time.perf_counter() - start > max_wall:
                break
            if self.exit_at_end and self.run.finished:
                break

    def close(self):
        self.stopping = True
        self.sock.close()
        self.run.close()


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m davit.live", description=__doc__.split("\n")[0])
    p.add_argument("deck")
    p.add_argument("--port", type=int, default=8765)
    p.add_argument("--speed", type=float, default=1.0, help="k x real time (default 1)")
    p.add_argument("--host", default="127.0.0.1", help="listen address (default loopback)")
    p.add_argument("--exit-at-end", action="store_true",
                   help="stop serving when the run ends (and print the summary)")
    a = p.parse_args(argv)
    server = LiveServer(a.deck, a.port, a.speed, a.host)
    server.exit_at_end = a.exit_at_end
    print(f"davit live: http://{a.host}:{server.port}/ ({a.deck}, {a.speed} x real time)",
          flush=True)
    try:
        server.serve()
    except KeyboardInterrupt:
        pass
    s = server.stats
    print(f"davit live: t = {server.run.time:.2f} s, {s['frames']} frames, "
          f"{s['deadline_misses']} deadline misses, worst step {s['worst_step_s'] * 1e3:.1f} ms, "
          f"{s['bad_messages']} bad messages", flush=True)
    server.close()


if __name__ == "__main__":
    main()
