#!/usr/bin/env python3
"""A chat-completions server on 127.0.0.1 that answers every request with one fixed failure, for the language-model
fault tests (llm_faults_cli.sh) and for timing a run against a failing server by hand.

usage: fake_llm_server.py --port-file FILE [--status 500] [--retry-after SECONDS] [--count-file FILE]
Writes the port it listens on (an ephemeral one) to --port-file, and the number of requests answered so far to
--count-file after each request. Runs until killed.
"""
import argparse
import http.server
import json
import threading

parser = argparse.ArgumentParser()
parser.add_argument("--port-file", required=True)
parser.add_argument("--status", type=int, default=500)
parser.add_argument("--retry-after", default=None)
parser.add_argument("--count-file", default=None)
args = parser.parse_args()
count = 0
lock = threading.Lock()


class Handler(http.server.BaseHTTPRequestHandler):
    def do_POST(self):
        global count
        self.rfile.read(int(self.headers.get("Content-Length", "0")))
        body = json.dumps({"error": {"message": f"fake failure {args.status}", "type": "server_error"}}).encode()
        self.send_response(args.status)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(body)))
        if args.retry_after is not None:
            self.send_header("Retry-After", args.retry_after)
        self.end_headers()
        self.wfile.write(body)
        with lock:
            count += 1
            if args.count_file:
                with open(args.count_file, "w") as f:
                    f.write(f"{count}\n")

    def log_message(self, *unused):
        pass


server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
with open(args.port_file + ".tmp", "w") as f:
    f.write(f"{server.server_address[1]}\n")
import os  # noqa: E402

os.replace(args.port_file + ".tmp", args.port_file)
server.serve_forever()
