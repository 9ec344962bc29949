#!/usr/bin/env python3
"""Many participants taking the web study at once, against a running `cbtl study serve`, timing every request.

Each simulated participant begins (coming back after the Retry-After of a 429, as the page does), then answers the thirteen pages as the study's page does (a picture's measure
fetched for each picture of an answers page, as a browser fetches the pictures), waiting a think time drawn from
[--think-min, --think-max] seconds before each answer. Participants start --stagger seconds apart. Bounded: at most
--participants threads, each request times out after --timeout seconds, the whole run stops after --deadline seconds.

Prints one JSON object: the requests made, those that failed (no answer or an HTTP error other than the expected),
the participants who finished, and latency quantiles (seconds) overall and per kind of request ("all" leaves out
the 429s of begins told to wait, which are listed apart).

  build/bin/cbtl study serve domains/feeding/feeding.cbtl --db /tmp/load.sqlite --port 8090 --no-pictures &
  python3 bench/study/study_load.py --port 8090 --participants 200
"""
import argparse
import http.client
import json
import random
import statistics
import sys
import threading
import time


def quantiles(values):
    if not values:
        return {}
    ordered = sorted(values)

    def at(q):
        return round(ordered[min(len(ordered) - 1, int(q * len(ordered)))], 4)

    return {"n": len(ordered), "median": at(0.5), "p95": at(0.95), "p99": at(0.99), "max": round(ordered[-1], 4),
            "mean": round(statistics.fmean(ordered), 4)}


class Participant(threading.Thread):
    def __init__(self, args, n, results):
        super().__init__(daemon=True)
        self.args, self.id, self.results = args, f"load-{args.prefix}-{n}", results
        self.random = random.Random(args.seed * 1000003 + n)
        self.key = ""
        self.connection = None

    def request(self, kind, method, path, body=None):
        headers = {"Content-Type": "application/json"}
        if self.key:
            headers["Authorization"] = "Bearer " + self.key
        data = json.dumps(body).encode() if body is not None else b""
        for attempt in range(2):  # a kept-alive connection the server closed is opened again once
            start = time.monotonic()
            try:
                if self.connection is None:
                    self.connection = http.client.HTTPConnection(self.args.host, self.args.port,
                                                                 timeout=self.args.timeout)
                self.connection.request(method, path, body=data if method == "POST" else None, headers=headers)
                response = self.connection.getresponse()
                payload = response.read()
                elapsed = time.monotonic() - start
                if response.status == 429 and kind == "begin":  # as the page does: come back when told
                    self.results.add("begin (told to wait)", elapsed, True)
                    time.sleep(float(response.getheader("Retry-After", "5")))
                    return self.request(kind, method, path, body)
                self.results.add(kind, elapsed, response.status == 200)
                if response.status != 200:
                    raise RuntimeError(f"{method} {path}: HTTP {response.status}: {payload[:200]!r}")
                return json.loads(payload)
            except (http.client.HTTPException, ConnectionError) as e:
                self.connection = None
                if attempt == 1:
                    self.results.add(kind, time.monotonic() - start, False)
                    raise RuntimeError(f"{method} {path}: {e}")
            except TimeoutError:
                self.connection = None
                self.results.add(kind, time.monotonic() - start, False)
                raise RuntimeError(f"{method} {path}: no answer in {self.args.timeout} s")

    def answer(self, state):
        page = state["page"]
        if page == "consent":
            return {"agree": True}
        if page == "demographics":
            return {"age": 30, "gender": "prefer-not-to-say", "gender_other": "", "robot_experience": False,
                    "fed_experience": False}
        if page == "rating":
            return {"likert": self.random.randint(1, 5)}
        if page == "answers":
            blocked = []
            for url in state.get("views", []):
                measure = self.request("picture", "GET", url[:-4] + ".json")
                blocked.append(measure["occlusion"] > 0.05)
            choices = state["choices"]
            return {"dip": self.random.choice(choices["dip"]), "signal": self.random.choice(choices["signal"]),
                    "verbosity": self.random.choice(choices["verbosity"]), "blocked": blocked}
        return {"comments": ""}

    def run(self):
        base = f"/api/participants/{self.id}"
        try:
            state = self.request("begin", "POST", base, {})
            self.key = state.get("key", "")
            elapsed = 0
            while state["page"] != "done":
                if time.monotonic() > self.results.deadline:
                    return
                think = self.random.uniform(self.args.think_min, self.args.think_max)
                time.sleep(think)
                elapsed += int(think * 1000)
                response = self.answer(state)
                record = {"trial_index": state["next_trial"], "kind": state["page"], "meal": state["meal"],
                          "elapsed_ms": elapsed, "rt_ms": int(think * 1000), "response": response}
                state = self.request(state["page"], "POST", base + "/records", record)["state"]
                if self.random.random() < self.args.reloads:  # a reload asks for the state again
                    state = self.request("state", "GET", base)
            self.results.finished()
        except Exception as e:  # noqa: BLE001 - every failure is counted and the first few shown
            self.results.fail(f"{self.id}: {e}")


class Results:
    def __init__(self, deadline):
        self.lock = threading.Lock()
        self.times, self.failures, self.done, self.deadline = {}, [], 0, deadline
        self.failed_requests = 0

    def add(self, kind, seconds, ok):
        with self.lock:
            self.times.setdefault(kind, []).append(seconds)
            if not ok:
                self.failed_requests += 1

    def fail(self, message):
        with self.lock:
            self.failures.append(message)

    def finished(self):
        with self.lock:
            self.done += 1


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--participants", type=int, default=200)
    p.add_argument("--think-min", type=float, default=2.0, help="seconds before an answer, at least")
    p.add_argument("--think-max", type=float, default=8.0, help="seconds before an answer, at most")
    p.add_argument("--stagger", type=float, default=0.05, help="seconds between participants' starts")
    p.add_argument("--reloads", type=float, default=0.1, help="the share of answers followed by a reload")
    p.add_argument("--timeout", type=float, default=60.0, help="seconds a request may take")
    p.add_argument("--deadline", type=float, default=600.0, help="seconds the whole run may take")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--prefix", default=str(int(time.time())), help="participant ids are load-PREFIX-N")
    args = p.parse_args()
    if not 1 <= args.participants <= 2000:
        sys.exit("--participants: 1 to 2000")
    start = time.monotonic()
    results = Results(start + args.deadline)
    threads = []
    for n in range(args.participants):
        t = Participant(args, n, results)
        t.start()
        threads.append(t)
        time.sleep(args.stagger)
    for t in threads:
        t.join(max(0.0, results.deadline - time.monotonic()) + args.timeout)
    # The 429s a begin was told to wait by are the admission limit at work, not the server's speed: apart.
    everything = [s for kind, times in results.times.items() if kind != "begin (told to wait)" for s in times]
    print(json.dumps({
        "participants": args.participants, "finished": results.done, "seconds": round(time.monotonic() - start, 1),
        "requests": len(everything), "failed_requests": results.failed_requests, "failures": results.failures[:5],
        "failed_participants": len(results.failures), "all": quantiles(everything),
        "by_kind": {kind: quantiles(times) for kind, times in sorted(results.times.items())},
        "think_seconds": [args.think_min, args.think_max]}, indent=1))
    return 0 if not results.failures and results.done == args.participants else 1


if __name__ == "__main__":
    sys.exit(main())
