#!/usr/bin/env python3
"""An HTTP proxy that forwards nothing: it writes every request it gets (GET, CONNECT, anything) as one
line to LOG and answers 403. A browser pointed at it shows whether a page asks the network for
anything. Prints the port it listens on, then serves until killed.
    logging_proxy.py LOG"""
import socketserver
import sys

LOG = sys.argv[1]


class Handler(socketserver.StreamRequestHandler):
    def handle(self):
        line = self.rfile.readline(8192).decode("latin-1").strip()
        if line:
            with open(LOG, "a") as f:
                f.write(line + "\n")
        self.wfile.write(b"HTTP/1.1 403 Forbidden\r\nContent-Length: 0\r\nConnection: close\r\n\r\n")


class Server(socketserver.ThreadingTCPServer):
    daemon_threads = True
    allow_reuse_address = True


with Server(("127.0.0.1", 0), Handler) as server:
    print(server.server_address[1], flush=True)
    server.serve_forever()
