#!/usr/bin/python3
"""A kapfix link client written from the .proto files and the wire rules alone (README,
"The link on the wire"): no code of the agent, kapfix-ctl or the station is used, so it shows
that another language can command the agent and read its streams.

The wire, in short:
- Commands: a DEALER (or REQ) socket to the agent's command port sends three frames
  [empty delimiter, b"command", kapfix.v1.Command bytes]; the agent answers every command with
  [empty delimiter, b"reply", kapfix.v1.Reply bytes].
- Streams: a SUB socket to the stream port receives [topic, bytes] (b"telemetry" carries
  kapfix.v1.Telemetry, b"state" kapfix.v1.AgentState, ...), filtered by topic.
- Every message starts with a kapfix.v1.Header: protocol_version 1 (the package is kapfix.v1),
  the agent's id (empty on a command: whichever agent answers), a sequence strictly increasing
  per sender from 1, and the send time [µs since the Unix epoch], which the agent checks for
  replays.

- An agent given keys (README, "Securing the link") speaks CurveZMQ only: the client's sockets
  carry the agent's public key and the station's key pair (kapfix-keygen's files, Z85 text).

Usage: kapfix_client.py --python-out DIR [--agent HOST] [--command-port P] [--stream-port P]
                        [--key STATION.key --agent-key AGENT.pub] state | mode MODE | watch N
  DIR holds the modules protoc made from proto/ (protoc -I proto --python_out DIR
  proto/kapfix/v1/*.proto). MODE: idle, fixate, ssp, ... (kapfix.v1.Mode without MODE_).
Exit codes: 0 ok, 1 the agent refused (its reason printed), 3 no answer.
"""
import argparse
import importlib
import sys
import time

PROTOCOL_VERSION = 1  # the package is kapfix.v1


class NoAnswer(Exception):
    """The agent did not answer within the timeout."""


class KeyFileError(Exception):
    """A key file that is missing or not kapfix-keygen's format (names the file)."""


def read_public_key(path):
    """The Z85 public key of a kapfix-keygen .pub file ("KEY NAME")."""
    try:
        with open(path) as f:
            words = f.read().split()
    except OSError as e:
        raise KeyFileError("%s: %s" % (path, e.strerror))
    if not words or len(words[0]) != 40:
        raise KeyFileError("%s: not a kapfix-keygen .pub file (a 40-character Z85 key first)" % path)
    return words[0].encode()


def read_key_pair(path):
    """(public, secret) Z85 keys of a kapfix-keygen .key file ("public-key = …" lines)."""
    keys = {}
    try:
        with open(path) as f:
            for line in f:
                name, sep, value = line.partition("=")
                if sep and not line.lstrip().startswith("#"):
                    keys[name.strip()] = value.strip().encode()
    except OSError as e:
        raise KeyFileError("%s: %s" % (path, e.strerror))
    if len(keys.get("public-key", b"")) != 40 or len(keys.get("secret-key", b"")) != 40:
        raise KeyFileError("%s: not a kapfix-keygen .key file (public-key and secret-key lines)"
                           % path)
    return keys["public-key"], keys["secret-key"]


class Client:
    """One station: a DEALER for commands, a SUB for streams. Not thread-safe.

    curve: None for plain TCP, or (agent public key, station public key, station secret key),
    Z85 bytes, for an agent that speaks CurveZMQ."""

    def __init__(self, zmq, pb, host="127.0.0.1", command_port=5555, stream_port=5556,
                 curve=None):
        self._zmq = zmq
        self._pb = pb
        self._context = zmq.Context()
        self._dealer = self._context.socket(zmq.DEALER)
        self._sub = self._context.socket(zmq.SUB)
        for socket in (self._dealer, self._sub):
            socket.setsockopt(zmq.LINGER, 0)
            if curve is not None:
                socket.setsockopt(zmq.CURVE_SERVERKEY, curve[0])
                socket.setsockopt(zmq.CURVE_PUBLICKEY, curve[1])
                socket.setsockopt(zmq.CURVE_SECRETKEY, curve[2])
        # No queueing before the agent is there: a command stamped before the agent started is
        # refused as a replay (ERROR_CODE_STALE_SEQUENCE), so it is stamped once it can go.
        self._dealer.setsockopt(zmq.IMMEDIATE, 1)
        # Watched before connecting, so that a refused key is heard of, not only waited out.
        self._events = self._dealer.get_monitor_socket(
            zmq.EVENT_HANDSHAKE_SUCCEEDED | zmq.EVENT_HANDSHAKE_FAILED_AUTH |
            zmq.EVENT_HANDSHAKE_FAILED_PROTOCOL | zmq.EVENT_HANDSHAKE_FAILED_NO_DETAIL |
            zmq.EVENT_DISCONNECTED)
        self._dealer.connect("tcp://%s:%d" % (host, command_port))
        self._sub.connect("tcp://%s:%d" % (host, stream_port))
        self._sequence = 0

    def handshake(self, timeout_s=10.0):
        """The command socket's first handshake: "ok", or why it failed ("auth": the agent
        refused this station's key; "failed": no common mechanism, e.g. plain TCP to an agent
        with keys, which drops the connection). Raises NoAnswer when none ends in time."""
        from zmq.utils.monitor import recv_monitor_message
        deadline = time.monotonic() + timeout_s
        while True:
            left_ms = int((deadline - time.monotonic()) * 1000)
            if left_ms <= 0 or not self._events.poll(left_ms):
                raise NoAnswer("no handshake with the agent within %.0f s" % timeout_s)
            event = recv_monitor_message(self._events)["event"]
            if event == self._zmq.EVENT_HANDSHAKE_SUCCEEDED:
                return "ok"
            if event == self._zmq.EVENT_HANDSHAKE_FAILED_AUTH:
                return "auth"
            return "failed"

    def close(self):
        self._dealer.disable_monitor()
        self._events.close()
        self._dealer.close()
        self._sub.close()
        self._context.term()

    def _stamp(self, header, protocol_version=PROTOCOL_VERSION, sequence=None):
        if sequence is None:
            self._sequence += 1
            sequence = self._sequence
        now_us = int(time.time() * 1e6)
        header.protocol_version = protocol_version
        header.sequence = sequence
        header.send_time_us = now_us
        header.capture_time_us = now_us

    def command(self, fill, timeout_s=10.0, protocol_version=PROTOCOL_VERSION, sequence=None):
        """Sends a Command filled by fill(command) and returns the agent's Reply."""
        command = self._pb["command"].Command()
        fill(command)
        deadline = time.monotonic() + timeout_s
        while True:
            left_ms = int((deadline - time.monotonic()) * 1000)
            if left_ms <= 0:
                raise NoAnswer("no connection to the agent within %.0f s" % timeout_s)
            if self._dealer.poll(left_ms, self._zmq.POLLOUT):
                break
        self._stamp(command.header, protocol_version, sequence)
        self._dealer.send_multipart([b"", b"command", command.SerializeToString()])
        while True:
            left_ms = int((deadline - time.monotonic()) * 1000)
            if left_ms <= 0 or not self._dealer.poll(left_ms):
                raise NoAnswer("no reply from the agent within %.0f s" % timeout_s)
            frames = self._dealer.recv_multipart()
            if len(frames) != 3 or frames[0] != b"" or frames[1] != b"reply":
                continue  # not a reply to us (nothing else comes on this socket)
            reply = self._pb["command"].Reply()
            reply.ParseFromString(frames[2])
            if reply.command_sequence in (0, command.header.sequence):
                return reply

    def state(self, **kwargs):
        return self.command(lambda c: c.request_state.SetInParent(), **kwargs)

    def mode_name(self, mode):
        """kapfix.v1.Mode as the short name set_mode takes ("fixate")."""
        return self._pb["types"].Mode.Name(mode)[len("MODE_"):].lower()

    def set_mode(self, mode_name, **kwargs):
        """Raises ValueError for a name that is no kapfix.v1.Mode."""
        mode = self._pb["types"].Mode.Value("MODE_" + mode_name.upper())
        return self.command(lambda c: setattr(c.set_mode, "mode", mode), **kwargs)

    def watch(self, topic, count, timeout_s=10.0):
        """The next `count` messages of a stream topic (b"telemetry": kapfix.v1.Telemetry)."""
        types = {b"telemetry": ("telemetry", "Telemetry"), b"state": ("state", "AgentState"),
                 b"log": ("log", "Log"), b"heartbeat": ("heartbeat", "Heartbeat")}
        module, name = types[topic]
        self._sub.setsockopt(self._zmq.SUBSCRIBE, topic)
        messages = []
        deadline = time.monotonic() + timeout_s
        while len(messages) < count:
            left_ms = int((deadline - time.monotonic()) * 1000)
            if left_ms <= 0 or not self._sub.poll(left_ms):
                raise NoAnswer("%d of %d %s messages within %.0f s" %
                               (len(messages), count, topic.decode(), timeout_s))
            frames = self._sub.recv_multipart()
            if len(frames) != 2 or frames[0] != topic:
                continue
            message = getattr(self._pb[module], name)()
            message.ParseFromString(frames[1])
            messages.append(message)
        self._sub.setsockopt(self._zmq.UNSUBSCRIBE, topic)
        return messages


def load_modules(python_out):
    """The protoc-made modules kapfix.v1's files became, by short name ("command", ...)."""
    sys.path.insert(0, python_out)
    return {name: importlib.import_module("kapfix.v1.%s_pb2" % name)
            for name in ("command", "types", "telemetry", "state", "log", "heartbeat")}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--python-out", required=True, help="protoc's Python modules of proto/")
    parser.add_argument("--agent", default="127.0.0.1")
    parser.add_argument("--command-port", type=int, default=5555)
    parser.add_argument("--stream-port", type=int, default=5556)
    parser.add_argument("--key", help="this station's kapfix-keygen .key file (CurveZMQ)")
    parser.add_argument("--agent-key", help="the agent's kapfix-keygen .pub file (CurveZMQ)")
    sub = parser.add_subparsers(dest="what", required=True)
    sub.add_parser("state", help="the agent's state")
    mode = sub.add_parser("mode", help="switch mode")
    mode.add_argument("mode", help="idle, fixate, follow, ssp, pss, calibrate, record_free_swing")
    watch = sub.add_parser("watch", help="telemetry lines")
    watch.add_argument("count", type=int)
    args = parser.parse_args(argv)
    try:
        import zmq  # Debian's python3-zmq
    except ImportError:
        print("kapfix_client.py needs python3-zmq", file=sys.stderr)
        return 2
    if (args.key is None) != (args.agent_key is None):
        print("--key and --agent-key go together (CurveZMQ needs both)", file=sys.stderr)
        return 2
    curve = None
    if args.key is not None:
        try:
            curve = (read_public_key(args.agent_key),) + read_key_pair(args.key)
        except KeyFileError as e:
            print(str(e), file=sys.stderr)
            return 2
    client = Client(zmq, load_modules(args.python_out), args.agent, args.command_port,
                    args.stream_port, curve)
    try:
        if args.what == "watch":
            for t in client.watch(b"telemetry", args.count):
                d = t.displacement
                print("frame %d mode %s displacement %.2f %.2f px confidence %.2f lock_lost %d" %
                      (t.frame_number, client.mode_name(t.mode), d.x_px + d.x_subpx,
                       d.y_px + d.y_subpx, t.confidence, t.lock_lost))
            return 0
        reply = client.state() if args.what == "state" else client.set_mode(args.mode)
        if not reply.ok:
            print("refused: %s" % reply.reason, file=sys.stderr)
            return 1
        if args.what == "state":
            s = reply.state
            print("agent %s mode %s slice %d" % (reply.header.agent_id, client.mode_name(s.mode),
                                                 s.slice))
        else:
            print("ok")
        return 0
    except NoAnswer as e:
        print(str(e), file=sys.stderr)
        return 3
    except ValueError as e:
        print(str(e), file=sys.stderr)
        return 2
    finally:
        client.close()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
