"""Client/server: pvserver does the work.

Starts `pvserver` (argv[1]) on a free local port, runs ClientServerScene.py in pvpython (argv[2])
against it, and checks that the client finished (its checks: the session is remote, the server's
Refracta Render Image matches Testing/Baselines/ParaViewRenderImage.png, the server's transfer-
function medium uses the client's colour map and opacity proxies). pvserver is stopped at the end.
"""
import os
import socket
import subprocess
import sys
import time

pvserver, pvpython = sys.argv[1], sys.argv[2]
with socket.socket() as s:
    s.bind(("localhost", 0))
    port = s.getsockname()[1]
server = subprocess.Popen([pvserver, "--server-port=%d" % port], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
try:
    deadline = time.time() + 60
    while time.time() < deadline:       # wait until it listens
        line = server.stdout.readline()
        print("[pvserver]", line.rstrip())
        if "Accepting connection" in line:
            break
        if server.poll() is not None:
            sys.exit("pvserver exited before accepting connections")
    scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ClientServerScene.py")
    client = subprocess.run([pvpython, scene, str(port)], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, timeout=240)
    print(client.stdout)
    assert client.returncode == 0 and "OK client/server" in client.stdout, "the client failed"
finally:
    server.terminate()
    try:
        server.wait(timeout=20)
    except subprocess.TimeoutExpired:
        server.kill()
print("OK")
