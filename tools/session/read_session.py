#!/usr/bin/python3
"""Reads a kapfix session file (kapfix-ctl record, the station's recording) with nothing but
protobuf: length-delimited kapfix.v1.SessionRecord messages (proto/kapfix/v1/session.proto),
each a varint size then the record. The first record names the format; every later one holds
a link message's receive time, topic and bytes, decoded here into its kapfix.v1 type.

Usage: read_session.py FILE [--python-out DIR]
  DIR holds the modules protoc made from proto/ (protoc -I proto --python_out DIR
  proto/kapfix/v1/*.proto); default: the current directory. Prints one line per message.
Old KFXREC01 recordings are not read here (kapfix-ctl and the station still replay them).
"""
import argparse
import importlib
import sys

# Which kapfix.v1 type travels under which topic (link/'s topic table says the same).
TOPIC_TYPES = {
    "telemetry": ("telemetry_pb2", "Telemetry"),
    "video": ("video_pb2", "VideoFrame"),
    "slices": ("slices_pb2", "SliceReport"),
    "pss": ("slices_pb2", "PssReport"),
    "calibration": ("calibration_pb2", "CalibrationReport"),
    "photo": ("photo_pb2", "Photo"),
    "log": ("log_pb2", "Log"),
    "heartbeat": ("heartbeat_pb2", "Heartbeat"),
    "command": ("command_pb2", "Command"),
    "reply": ("command_pb2", "Reply"),
    "state": ("state_pb2", "AgentState"),
}


class SessionError(Exception):
    """The file is not a session recording, or is cut short or corrupted (names the offset)."""


def _read_varint(data, pos):
    """The varint at data[pos:] and the position after it; None when the data ends inside it."""
    value, shift = 0, 0
    while pos < len(data) and shift < 64:
        byte = data[pos]
        pos += 1
        value |= (byte & 0x7F) << shift
        if byte < 0x80:
            return value, pos
        shift += 7
    return None


def read_records(data, session_pb2):
    """Yields (offset, SessionRecord) for every record of the file's bytes."""
    pos = 0
    while pos < len(data):
        start = pos
        varint = _read_varint(data, pos)
        if varint is None or varint[1] + varint[0] > len(data):
            raise SessionError("cut short or corrupted in the record at byte %d" % start)
        size, pos = varint
        record = session_pb2.SessionRecord()
        try:
            record.ParseFromString(data[pos:pos + size])
        except Exception as error:  # protobuf raises DecodeError, or others on some backends
            raise SessionError("corrupted record at byte %d: %s" % (start, error)) from error
        pos += size
        yield start, record


def read_session(path):
    """Yields (receive_time_us, topic, decoded message or None) for each recorded message."""
    session_pb2 = importlib.import_module("kapfix.v1.session_pb2")
    with open(path, "rb") as file:
        data = file.read()
    if data.startswith(b"KFXREC01"):
        raise SessionError("%s is an old KFXREC01 recording: replay it with kapfix-ctl or the "
                           "station; this reader reads the kapfix-session format" % path)
    records = read_records(data, session_pb2)
    first = next(records, None)
    if first is None or first[1].WhichOneof("record") != "format" or \
            first[1].format.name != "kapfix-session":
        raise SessionError("%s is not a kapfix session recording" % path)
    if first[1].format.version != 1:
        raise SessionError("%s is of version %d; this reader reads version 1"
                           % (path, first[1].format.version))
    for _, record in records:
        if record.WhichOneof("record") != "message":
            continue
        topic = record.message.topic.decode("utf-8", "replace")
        message = None
        if topic in TOPIC_TYPES:
            module, name = TOPIC_TYPES[topic]
            message = getattr(importlib.import_module("kapfix.v1." + module), name)()
            message.ParseFromString(record.message.payload)
        yield record.message.receive_time_us, topic, message


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("--python-out", default=".", help="protoc --python_out folder")
    arguments = parser.parse_args()
    sys.path.insert(0, arguments.python_out)
    try:
        for time_us, topic, message in read_session(arguments.file):
            sequence = message.header.sequence if message is not None else "-"
            print("%d %s sequence %s" % (time_us, topic, sequence))
    except (SessionError, OSError) as error:
        print("read_session.py: %s" % error, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
