#!/usr/bin/env python3
"""The coffee domain's simulated machine and drinker: an external simulator for cbtl (protocol 1).

cbtl starts this program (the `simulator` line of coffee.cbtl), writes one JSON request per line on its stdin
and reads one JSON answer per line from its stdout; docs/simulator-protocol.md describes every message. Anything
else this program wants to say goes to stderr (cbtl shows it, prefixed "simulator| ").

The drinker has a hidden temperature interval and a hidden strength interval per cup size. CBTL is never told
them: it learns them from the drinker's verdicts (the `tasteCritique` feedback event). Only the standard library
is used.
"""

import json
import random
import sys

PROTOCOL = 1
CUP_ML = {"small": 150.0, "medium": 250.0, "large": 350.0}
TANK_ML = 1200.0
HOPPER_G = 60.0


class Drinker:
    """The person: shared by the training world and its evaluation twins, as the protocol asks."""

    def __init__(self, participant):
        if participant < 0:  # the default drinker
            self.temperature = [66.0, 74.0]
            self.strength = {"small": [8.0, 10.0], "medium": [7.0, 9.0], "large": [5.5, 7.5]}
        else:  # participant n: their own tastes, the same for the same n
            rng = random.Random(participant)
            low = rng.uniform(58.0, 75.0)
            self.temperature = [low, low + rng.uniform(5.0, 10.0)]
            self.strength = {}
            for size in CUP_ML:
                low = rng.uniform(4.5, 9.0)
                self.strength[size] = [low, low + rng.uniform(1.5, 3.0)]

    def shift(self, rng, lo, hi):
        """Tastes change: every interval is rescaled around its centre by a factor drawn from [lo, hi]."""
        for interval in [self.temperature] + [self.strength[s] for s in sorted(self.strength)]:
            centre = (interval[0] + interval[1]) / 2
            half = (interval[1] - interval[0]) / 2 * rng.uniform(lo, hi)
            interval[0], interval[1] = centre - half, centre + half

    def taste(self, size, temperature, strength):
        t_lo, t_hi = self.temperature
        s_lo, s_hi = self.strength[size]
        heat = "tooCold" if temperature < t_lo else "tooHot" if temperature > t_hi else "heatGood"
        body = "tooWeak" if strength < s_lo else "tooStrong" if strength > s_hi else "bodyGood"
        return heat, body


class Machine:
    """One world: the machine's tank and hopper, with its own random numbers."""

    def __init__(self, drinker, options, trains):
        self.drinker = drinker
        self.options = options
        self.trains = trains  # the training world shifts the drinker's tastes; its twins never do
        self.steps = 0
        self.reset(0)

    def reset(self, seed):
        self.rng = random.Random(seed)
        self.water = self.rng.uniform(400.0, TANK_ML)
        self.beans = self.rng.uniform(20.0, HOPPER_G)

    def observe(self):
        return {"waterLeft": self.water, "beansLeft": self.beans}

    def brew(self, args):
        size, strength, temperature = args["size"], args["strength"], args["temperature"]
        if CUP_ML[size] > self.water or strength * CUP_ML[size] / 100 > self.beans:
            # The CSP's hard constraints forbid this; a simulator still checks what it is asked to do.
            return {"status": "ignored", "step": True, "done": True, "failed": True,
                    "message": "not enough water or beans for a %s cup" % size}
        self.water -= CUP_ML[size]
        self.beans -= strength * CUP_ML[size] / 100
        heat, body = self.drinker.taste(size, temperature, strength)
        result = {
            "status": "applied", "step": True, "done": True,
            "satisfaction": 1.0 if heat == "heatGood" and body == "bodyGood" else -1.0,
            "feedback": [{"event": "tasteCritique",
                          "args": {"size": size, "temperature": temperature, "strength": strength,
                                   "heat": heat, "body": body}}],
            "preferences": {"temperature": heat == "heatGood", "strength": body == "bodyGood"},
        }
        self.refill()
        self.advance(result)
        return result

    def idle(self):
        result = {"status": "applied", "step": True}
        self.refill()
        self.advance(result)
        return result

    def refill(self):
        # Someone tops the machine up once it runs low.
        if self.water < 400.0:
            self.water = TANK_ML
        if self.beans < 15.0:
            self.beans = HOPPER_G

    def advance(self, result):
        self.steps += 1
        every = self.options.get("shift_every", 0)
        if self.trains and every > 0 and self.steps % every == 0:
            self.drinker.shift(self.rng, self.options.get("shift_lo", 0.9), self.options.get("shift_hi", 1.1))
            if self.options.get("announce_shifts", False):
                result["preferences_changed"] = True


def manifest():
    return {"protocol": PROTOCOL, "simulator": "coffee_sim.py",
            "observations": ["waterLeft", "beansLeft"], "actions": ["brew"],
            "feedback": ["tasteCritique"], "tasks": [], "preferences": ["temperature", "strength"]}


def main():
    worlds = {}
    drinker = None
    options = {}
    for line in sys.stdin:
        if not line.strip():
            continue
        request = json.loads(line)
        op = request.get("op")
        answer = {"id": request.get("id"), "ok": True}
        try:
            if op == "hello":
                if request.get("protocol") != PROTOCOL:
                    raise ValueError("this simulator speaks protocol %d" % PROTOCOL)
                options = request.get("options", {})
                drinker = Drinker(options.get("participant", -1))
                worlds[0] = Machine(drinker, options, trains=True)
                answer.update(manifest())
            elif op == "reset":
                worlds[request["world"]].reset(request["seed"])
            elif op == "observe":
                answer["observation"] = worlds[request["world"]].observe()
            elif op == "act":
                if request["action"] != "brew":
                    raise ValueError("no action '%s'" % request["action"])
                answer.update(worlds[request["world"]].brew(request["args"]))
            elif op == "idle":
                answer.update(worlds[request["world"]].idle())
            elif op == "twin":
                world = max(worlds) + 1
                worlds[world] = Machine(drinker, options, trains=False)
                answer["world"] = world
            elif op == "close":
                worlds.pop(request["world"], None)
            elif op == "bye":
                print(json.dumps(answer), flush=True)
                return
            else:
                raise ValueError("no request '%s'" % op)
        except (KeyError, ValueError) as error:
            answer = {"id": request.get("id"), "ok": False, "error": str(error)}
        print(json.dumps(answer), flush=True)


if __name__ == "__main__":
    main()
