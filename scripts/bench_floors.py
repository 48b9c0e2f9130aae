#!/usr/bin/env python3
"""Floors for moving a frame's bytes: memcpy of N bytes, and the same bytes over a
loopback TCP connection (127.0.0.1, one sender thread, the receiver reading into a preallocated
buffer). Prints `memcpy_ms X loopback_ms Y`, the fastest of --rounds rounds of each."""
import argparse
import socket
import threading
import time


def memcpy_ms(data, target):
    start = time.perf_counter()
    target[:] = data  # one memcpy into pages already touched
    return (time.perf_counter() - start) * 1e3


def loopback_ms(data):
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    port = server.getsockname()[1]

    def send():
        with socket.create_connection(("127.0.0.1", port)) as out:
            out.sendall(data)

    sender = threading.Thread(target=send)
    buffer = bytearray(data)  # touched before the clock starts
    view = memoryview(buffer)
    start = time.perf_counter()
    sender.start()
    conn, _ = server.accept()
    got = 0
    while got < len(data):
        n = conn.recv_into(view[got:], len(data) - got)
        if n == 0:
            break
        got += n
    elapsed = (time.perf_counter() - start) * 1e3
    sender.join()
    conn.close()
    server.close()
    assert got == len(data), f"received {got} of {len(data)} bytes"
    return elapsed


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("bytes", type=int)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    data = bytes(range(256)) * (args.bytes // 256) + bytes(args.bytes % 256)
    target = bytearray(data)
    print("memcpy_ms %.3f loopback_ms %.3f" % (
        min(memcpy_ms(data, target) for _ in range(args.rounds)),
        min(loopback_ms(data) for _ in range(args.rounds))))


if __name__ == "__main__":
    main()
