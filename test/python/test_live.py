"""`python3 -m davit.live`: the launch paced to the wall clock and served over a WebSocket on
loopback at 30 Hz; a trainee's commands act on the run; malformed and hostile messages are
counted and never stop it; the page loads and renders in a real headless Chromium."""
import base64
import json
import os
import pathlib
import shutil
import socket
import struct
import subprocess
import sys
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPEED = 4.0
# calm water and no wind: the boat's height says what the winch does
CALM = """&simulation scene = 'launch', t_end = 120.0, dt = 1.0e-3, output_interval = 0.02 /
&boat position = 0.0, 13.3, -15.0 /
&rigging reeving = 'a', sheaves = 'quasi_static', lumps = 0, drum_speed = 0.7, release = .false. /
&wind speed = 0.0 /
"""


@pytest.fixture()
def server(tmp_path):
    deck = tmp_path / "calm.nml"
    deck.write_text(CALM)
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    proc = subprocess.Popen([sys.executable, "-m", "davit.live", str(deck), "--port", "0",
                             "--speed", str(SPEED)], stdout=subprocess.PIPE, text=True,
                            env=env, cwd=ROOT)
    line = proc.stdout.readline()
    assert "http://127.0.0.1:" in line, line
    port = int(line.split("http://127.0.0.1:")[1].split("/")[0])
    yield port
    proc.terminate()
    proc.wait(timeout=10)


def connect(port):
    s = socket.create_connection(("127.0.0.1", port), timeout=10)
    key = base64.b64encode(os.urandom(16)).decode()
    s.sendall(f"GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
              f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n".encode())
    head = b""
    while b"\r\n\r\n" not in head:
        head += s.recv(1)
    assert b"101" in head.split(b"\r\n")[0]
    return s


def recv_exact(s, n):
    b = b""
    while len(b) < n:
        chunk = s.recv(n - len(b))
        assert chunk, "server closed"
        b += chunk
    return b


def recv_state(s):
    b0, b1 = recv_exact(s, 2)
    n = b1 & 0x7F
    if n == 126:
        n = struct.unpack("!H", recv_exact(s, 2))[0]
    elif n == 127:
        n = struct.unpack("!Q", recv_exact(s, 8))[0]
    return json.loads(recv_exact(s, n))


def send(s, payload, opcode=0x1, masked=True):
    data = payload if isinstance(payload, bytes) else payload.encode()
    mask = os.urandom(4)
    n = len(data)
    head = bytes([0x80 | opcode])
    bit = 0x80 if masked else 0
    if n < 126:
        head += bytes([bit | n])
    elif n < 65536:
        head += bytes([bit | 126]) + struct.pack("!H", n)
    else:
        head += bytes([bit | 127]) + struct.pack("!Q", n)
    if masked:
        head += mask
        data = bytes(c ^ mask[i % 4] for i, c in enumerate(data))
    s.sendall(head + data)


def states_for(s, seconds):
    out, end = [], time.monotonic() + seconds
    while time.monotonic() < end:
        out.append(recv_state(s))
    return out


def test_handshake_key_is_rfc_6455s_example():
    """RFC 6455, section 1.3: key dGhlIHNhbXBsZSBub25jZQ== -> s3pPLMBiTxaQ9kYGzzhZRbK+xOo=."""
    sys.path.insert(0, str(ROOT / "python"))
    from davit.live import accept_key
    assert accept_key("dGhlIHNhbXBsZSBub25jZQ==") == "s3pPLMBiTxaQ9kYGzzhZRbK+xOo="


def test_state_at_30_hz_paced_to_the_wall_clock(server):
    """>= 30 frames a second; the run's time advances at SPEED x the wall time (10 %)."""
    s = connect(server)
    recv_state(s)
    states = states_for(s, 2.0)
    wall = states[-1]["wall"] - states[0]["wall"]
    assert len(states) / wall >= 29.0
    assert (states[-1]["t"] - states[0]["t"]) / wall == pytest.approx(SPEED, rel=0.1)
    assert states[-1]["stats"]["deadline_misses"] == 0


def test_malformed_messages_never_stop_the_run(server):
    """Bad JSON, bytes that are not UTF-8, unknown commands, values out of range, a binary
    frame, a frame over the size limit (on its own connection): all
    counted, the run and the other client go on."""
    s = connect(server)
    t0 = recv_state(s)["t"]
    for bad in ["{not json", b"\xff\xfe\x00", '{"cmd": "explode"}', '{"cmd": "speed", '
                '"value": 1e308}', '{"cmd": "speed", "value": "fast"}', "[1, 2]", "null"]:
        send(s, bad)
    send(s, b"\x00\x01", opcode=0x2)
    hostile = connect(server)
    send(hostile, "x" * 100000)
    hostile.close()
    time.sleep(1.0)
    states = states_for(s, 0.5)
    assert states[-1]["t"] > t0 + 0.5 * SPEED
    assert states[-1]["stats"]["bad_messages"] >= 9
    assert states[-1]["error"] is None


def test_scripted_trainee_stops_lowers_and_releases(server):
    """Stop (the boat's height holds), lower again (it descends), then release: the state
    reports the release."""
    s = connect(server)
    recv_state(s)
    send(s, json.dumps({"cmd": "stop"}))
    states_for(s, 1.0)
    a = states_for(s, 1.0)
    assert abs(a[-1]["boat"][2] - a[0]["boat"][2]) < 0.05
    send(s, json.dumps({"cmd": "speed", "value": 1.4}))
    b = states_for(s, 1.5)
    assert b[-1]["boat"][2] - b[0]["boat"][2] > 0.3 * SPEED * 1.5 * 0.5
    send(s, json.dumps({"cmd": "release"}))
    c = states_for(s, 0.5)
    assert c[-1]["events"]["release"] is not None


def chromium():
    for name in ("chromium", "chromium-browser"):
        if shutil.which(name):
            return name
    return None


def test_page_in_headless_chromium(server, tmp_path):
    """The page loads in a real headless Chromium, the WebGL scene is not blank, and a
    scripted trainee (the page's buttons) stops, resumes the lowering, and once the page
    reports the boat waterborne releases it: the page shows 'released'."""
    webdriver = pytest.importorskip("selenium.webdriver")
    if chromium() is None or shutil.which("chromedriver") is None:
        pytest.skip("chromium and chromium-driver are not installed (bash make.sh test "
                    "installs them)")
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.by import By
    opts = Options()
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                "--window-size=800,600"):
        opts.add_argument(arg)
    opts.binary_location = shutil.which(chromium())
    driver = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=opts)
    try:
        driver.get(f"http://127.0.0.1:{server}/")
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and not driver.find_element(By.TAG_NAME, "body") \
                .get_attribute("data-frames"):
            time.sleep(0.2)
        assert driver.find_element(By.TAG_NAME, "body").get_attribute("data-frames")
        png = tmp_path / "live.png"
        driver.save_screenshot(str(png))
        pixels = driver.execute_script("""
            const c = document.getElementById('view'), gl = c.getContext('webgl');
            const px = new Uint8Array(4 * 64);
            gl.readPixels(Math.floor(c.width / 2) - 32, Math.floor(c.height / 2), 64, 1,
                          gl.RGBA, gl.UNSIGNED_BYTE, px);
            return Array.from(px);""")
        colours = {tuple(pixels[i:i + 3]) for i in range(0, len(pixels), 4)}
        assert len(colours) >= 2, colours   # sky, sea, hull or boat: not one flat colour
        assert png.stat().st_size > 5000
        # the trainee stops the lowering, resumes it, waits for the boat to be waterborne
        # (the HUD's status from the run's own event) and releases the hooks
        def status_becomes(text, seconds):
            end = time.monotonic() + seconds
            while time.monotonic() < end and driver.find_element(By.ID, "status").text != text:
                time.sleep(0.2)
            return driver.find_element(By.ID, "status").text == text
        driver.find_element(By.ID, "stop").click()
        time.sleep(1.0)
        assert driver.find_element(By.ID, "status").text == "hanging"
        driver.find_element(By.ID, "lower").click()
        # 15 m at the winch's 0.7 m/s (x SPEED) plus the stop: ~6 s of wall time
        assert status_becomes("waterborne", 40.0), driver.find_element(By.ID, "hud").text
        assert "waterborne" in driver.find_element(By.ID, "hud").text
        driver.find_element(By.ID, "release").click()
        assert status_becomes("released", 10.0), driver.find_element(By.ID, "hud").text
    finally:
        driver.quit()
