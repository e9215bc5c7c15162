#!/usr/bin/python3
"""A peer no kapfix code went into commands the real agent: tools/python_client/kapfix_client.py
(Debian's python3-zmq and python3-protobuf, modules protoc makes from proto/) against
kapfix-agent in simulation over loopback TCP. It reads the agent's state, switches it to fixate
and reads its telemetry; a command of another protocol version, a replayed sequence and an
out-of-range gain are refused with the error code and a reason naming the problem.

Then an agent given CurveZMQ keys (kapfix-keygen's files): the client with an authorised key
pair is answered, one with a key the agent does not list hears "auth" refused at the handshake,
and a plain client gets no handshake through.

Usage: python_client_test.py PROTOC PROTO_DIR KAPFIX_AGENT CLIENT_PY KAPFIX_KEYGEN
Exits 77 (ctest: skipped) with a message when python3-zmq or python3-protobuf is missing.
Every wait is on the agent's answer, bounded only to end a hang.
"""
import glob
import importlib.util
import json
import os
import socket
import subprocess
import sys
import tempfile

SKIPPED = 77
ANSWER_S = 60.0  # [s] bound on any one answer: a hang, not a slow machine, should fail


def free_port_pair():
    """Two consecutive free TCP ports on loopback (commands, streams)."""
    for _ in range(50):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        if port >= 65535:
            continue
        with socket.socket() as a, socket.socket() as b:
            try:
                a.bind(("127.0.0.1", port))
                b.bind(("127.0.0.1", port + 1))
            except OSError:
                continue
        return port
    raise RuntimeError("no two consecutive free ports on loopback")


def main():
    protoc, proto_dir, agent_binary, client_path, keygen = sys.argv[1:6]
    try:
        import zmq
        import google.protobuf  # noqa: F401  (only whether it is there)
    except ImportError:
        print("skipped: needs python3-zmq and python3-protobuf "
              "(apt-get install python3-zmq python3-protobuf)")
        return SKIPPED
    failures = []

    def check(condition, what):
        if not condition:
            failures.append(what)

    with tempfile.TemporaryDirectory() as folder:
        protos = sorted(glob.glob(os.path.join(proto_dir, "kapfix", "v1", "*.proto")))
        subprocess.run([protoc, "-I", proto_dir, "--python_out", folder] + protos, check=True)
        spec = importlib.util.spec_from_file_location("kapfix_client", client_path)
        kapfix_client = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(kapfix_client)
        pb = kapfix_client.load_modules(folder)
        command_pb2, types_pb2 = pb["command"], pb["types"]

        def start_agent(name, link):
            """kapfix-agent in simulation, idle, with `link` (the config's "link" object) on
            two free loopback ports; (process, command port, log path)."""
            port = free_port_pair()
            link = dict(link, command="tcp://127.0.0.1:%d" % port,
                        stream="tcp://127.0.0.1:%d" % (port + 1))
            config = os.path.join(folder, name + ".json")
            with open(config, "w") as f:
                json.dump({"link": link}, f)
            log_path = os.path.join(folder, name + ".log")
            with open(log_path, "w") as log:
                process = subprocess.Popen(
                    [agent_binary, "--config", config, "--sim", "--mode", "idle", "--no-resume",
                     "--state-dir", os.path.join(folder, name + "_state")],
                    stdout=log, stderr=subprocess.STDOUT)
            return process, port, log_path

        def stop_agent(process):
            process.terminate()
            try:
                code = process.wait(timeout=ANSWER_S)
            except subprocess.TimeoutExpired:
                process.kill()
                code = process.wait()
                failures.append("the agent did not stop on SIGTERM")
            check(code == 0, "the agent exited with %s on SIGTERM" % code)

        agent, port, log_path = start_agent("plain", {})
        client = kapfix_client.Client(zmq, pb, "127.0.0.1", port, port + 1)
        try:
            state = client.state(timeout_s=ANSWER_S)
            check(state.ok, "request_state refused: %s" % state.reason)
            check(state.state.mode == types_pb2.MODE_IDLE,
                  "mode %s, not idle" % client.mode_name(state.state.mode))
            check(state.header.protocol_version == 1,
                  "reply's protocol version %d" % state.header.protocol_version)
            agent_id = state.header.agent_id
            check(agent_id != "", "the reply names no agent")

            fixate = client.set_mode("fixate", timeout_s=ANSWER_S)
            check(fixate.ok, "set_mode fixate refused: %s" % fixate.reason)
            # Telemetry of frames processed before the switch may still be on its way.
            telemetry = [t for t in client.watch(b"telemetry", 40, timeout_s=ANSWER_S)
                         if t.mode == types_pb2.MODE_FIXATE]
            check(len(telemetry) >= 5, "%d of 40 telemetry messages in fixate" % len(telemetry))
            sequences = [t.header.sequence for t in telemetry]
            check(all(a < b for a, b in zip(sequences, sequences[1:])),
                  "telemetry sequences not increasing: %s" % sequences[:10])
            check(all(t.header.agent_id == agent_id for t in telemetry),
                  "telemetry from another agent id")
            check(any(t.confidence > 0 for t in telemetry), "no match in the fixate telemetry")

            wrong = client.state(timeout_s=ANSWER_S, protocol_version=2)
            check(not wrong.ok and wrong.error == command_pb2.ERROR_CODE_WRONG_VERSION,
                  "protocol version 2: ok=%s error=%s" % (wrong.ok, wrong.error))
            check("2" in wrong.reason and "1" in wrong.reason,
                  "the refusal of version 2 names neither version: %r" % wrong.reason)

            replayed = client.state(timeout_s=ANSWER_S, sequence=1)
            check(not replayed.ok and replayed.error == command_pb2.ERROR_CODE_STALE_SEQUENCE,
                  "replayed sequence 1: ok=%s error=%s" % (replayed.ok, replayed.error))

            def too_high(command):
                command.set_gains.p = 1000.0
            gain = client.command(too_high, timeout_s=ANSWER_S)
            check(not gain.ok and gain.error == command_pb2.ERROR_CODE_OUT_OF_RANGE,
                  "p = 1000: ok=%s error=%s" % (gain.ok, gain.error))
            check("p" in gain.reason and "10" in gain.reason,
                  "the refusal of p = 1000 names neither the field nor its range: %r"
                  % gain.reason)

            after = client.state(timeout_s=ANSWER_S)
            check(after.ok and after.state.mode == types_pb2.MODE_FIXATE,
                  "after the refusals: ok=%s mode %s" % (after.ok,
                                                         client.mode_name(after.state.mode)))
            check(abs(after.state.gains.p - 1.0) < 1e-6,
                  "the refused gain changed p to %s" % after.state.gains.p)
        except kapfix_client.NoAnswer as e:
            failures.append(str(e))
        finally:
            client.close()
            stop_agent(agent)

        # CurveZMQ: kapfix-keygen's files, the agent listing the laptop's key only.
        for name in ("agent", "laptop", "stranger"):
            subprocess.run([keygen, name], cwd=folder, check=True, stdout=subprocess.DEVNULL)
        def key(name):
            return os.path.join(folder, name)

        with open(key("authorized_keys"), "w") as f, open(key("laptop.pub")) as pub:
            f.write(pub.read())
        secure, secure_port, secure_log = start_agent(
            "secure", {"curve_secret_key_file": key("agent.key"),
                       "curve_authorized_keys_file": key("authorized_keys")})
        agent_key = kapfix_client.read_public_key(key("agent.pub"))
        try:
            for name, expected in (("laptop", "ok"), ("stranger", "auth"), (None, "failed")):
                curve = None if name is None else (
                    (agent_key,) + kapfix_client.read_key_pair(key(name + ".key")))
                peer = kapfix_client.Client(zmq, pb, "127.0.0.1", secure_port, secure_port + 1,
                                            curve)
                try:
                    shake = peer.handshake(timeout_s=ANSWER_S)
                    check(shake == expected, "%s's handshake: %s, not %s" % (name, shake, expected))
                    if expected == "ok":
                        answer = peer.state(timeout_s=ANSWER_S)
                        check(answer.ok, "%s's request_state refused: %s" % (name, answer.reason))
                finally:
                    peer.close()
        except kapfix_client.NoAnswer as e:
            failures.append("CurveZMQ: " + str(e))
        finally:
            stop_agent(secure)
        if failures:
            tails = ""
            for path in (log_path, secure_log):
                with open(path) as log:
                    tails += "\n%s (end):\n%s" % (os.path.basename(path), log.read()[-2000:])
            print("FAILED:\n  " + "\n  ".join(failures) + tails)
            return 1
    print("ok: state, fixate, %d telemetry messages, three refusals with reasons; CurveZMQ: the "
          "listed key answered, an unlisted one refused at the handshake, a plain peer's "
          "handshake failed" % len(telemetry))
    return 0


if __name__ == "__main__":
    sys.exit(main())
