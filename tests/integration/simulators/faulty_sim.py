#!/usr/bin/env python3
"""A coffee simulator that goes wrong in one chosen way, for tests/integration/external_simulator.sh.

usage: faulty_sim.py COFFEE_DIR MODE
The coffee domain's own simulator (COFFEE_DIR/coffee_sim.py) answers every request, except where MODE makes this
program misbehave: crash, print noise on stdout, hang, send an undeclared event, a manifest that does not fit, a
newer protocol, an ill-typed observation, a refusal, a step result with an unknown field, a KeyError when asked for
an evaluation twin, noise on stdout when asked to idle, or a training world whose tank runs dry (every later request
unsolvable).
"""

import json
import sys
import time

sys.path.insert(0, sys.argv[1])
import coffee_sim  # noqa: E402

MODE = sys.argv[2]


def main():
    worlds = {}
    drinker = None
    for line in sys.stdin:
        request = json.loads(line)
        op, rid = request["op"], request["id"]
        answer = {"id": rid, "ok": True}
        if op == "hello":
            drinker = coffee_sim.Drinker(-1)
            worlds[0] = coffee_sim.Machine(drinker, request["options"], trains=True)
            answer.update(coffee_sim.manifest())
            if MODE == "manifest":
                answer.update({"observations": ["waterLeft", "outsideTemperature"], "actions": [],
                               "feedback": ["tasteCritique", "spilled"], "tasks": ["makeTea"]})
            if MODE == "protocol2":
                answer["protocol"] = 2
        elif op == "reset":
            worlds[request["world"]].reset(request["seed"])
        elif op == "observe":
            answer["observation"] = worlds[request["world"]].observe()
            if MODE == "dry" and request["world"] == 0 and rid > 8:
                answer["observation"]["waterLeft"] = 0.0  # the training world's tank runs dry and is never refilled
            if MODE == "bad-observation":
                answer["observation"]["waterLeft"] = "plenty"
        elif op == "act":
            if MODE == "crash" and rid >= 8:
                print("the boiler burst at request %d" % rid, file=sys.stderr, flush=True)
                sys.exit(3)
            if MODE == "hang":
                time.sleep(1000)
            if MODE == "noise":
                print("brewing a %s cup" % request["args"]["size"], flush=True)
            if MODE == "refuse":
                answer = {"id": rid, "ok": False, "error": "the grinder jammed"}
            else:
                answer.update(worlds[request["world"]].brew(request["args"]))
            if MODE == "undeclared-event":
                answer["feedback"].append({"event": "spilled", "args": {}})
            if MODE == "unknown-field":
                answer["satisfation"] = 1
            if MODE == "wrong-type":
                answer["feedback"][0]["args"]["heat"] = "lukewarm"
        elif op == "twin":
            if MODE == "twin-keyerror":
                raise KeyError("twin")  # a traceback on stderr, then exit status 1
            world = max(worlds) + 1
            worlds[world] = coffee_sim.Machine(drinker, {}, trains=False)
            answer["world"] = world
        elif op == "close":
            worlds.pop(request["world"], None)
        elif op == "idle":
            if MODE == "idle-noise":
                print("waiting...", flush=True)
            answer.update(worlds[request["world"]].idle())
        print(json.dumps(answer), flush=True)
        if op == "bye":
            return


if __name__ == "__main__":
    main()
