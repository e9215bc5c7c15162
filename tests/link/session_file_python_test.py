#!/usr/bin/python3
"""The session file is readable by any protobuf client: Python's protobuf, with modules protoc
makes from proto/, reads a file SessionRecorder wrote (tools/session/read_session.py).

Usage: session_file_python_test.py PROTOC PROTO_DIR SAMPLE_WRITER READ_SESSION_PY
Exits 77 (ctest: skipped) with a message when python3-protobuf is not installed.
"""
import glob
import importlib.util
import os
import subprocess
import sys
import tempfile

SKIPPED = 77


def main():
    protoc, proto_dir, sample_writer, reader_path = sys.argv[1:5]
    try:
        import google.protobuf  # noqa: F401  (only whether it is there)
    except ImportError:
        print("skipped: python3-protobuf is not installed (apt-get install python3-protobuf)")
        return SKIPPED
    with tempfile.TemporaryDirectory() as folder:
        protos = sorted(glob.glob(os.path.join(proto_dir, "kapfix", "v1", "*.proto")))
        subprocess.run([protoc, "-I", proto_dir, "--python_out", folder] + protos, check=True)
        session = os.path.join(folder, "sample.kfxrec")
        subprocess.run([sample_writer, session], check=True)
        sys.path.insert(0, folder)
        spec = importlib.util.spec_from_file_location("read_session", reader_path)
        reader = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(reader)
        messages = list(reader.read_session(session))

        failures = []
        topics = [topic for _, topic, _ in messages]
        if topics != ["telemetry"] * 5 + ["log"]:
            failures.append("topics: %s" % topics)
        times = [time_us for time_us, _, _ in messages]
        if times != [1001, 1002, 1003, 1004, 1005, 1006]:
            failures.append("receive times: %s" % times)
        frames = [m.frame_number for _, topic, m in messages if topic == "telemetry"]
        if frames != [10, 11, 12, 13, 14]:
            failures.append("telemetry frame numbers: %s" % frames)
        if messages and (messages[-1][2].text != "sample" or
                         messages[-1][2].header.protocol_version != 1):
            failures.append("log: %s" % messages[-1][2])

        # A cut file: the reader names the offset instead of returning half a record.
        with open(session, "rb") as file:
            data = file.read()
        with open(session, "wb") as file:
            file.write(data[:-2])
        try:
            list(reader.read_session(session))
            failures.append("a cut file was read without an error")
        except reader.SessionError as error:
            if "at byte" not in str(error):
                failures.append("cut file: %s" % error)
    for failure in failures:
        print("FAILED: " + failure)
    if not failures:
        print("read %d messages in Python" % len(messages))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
