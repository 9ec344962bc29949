// SimulatorServer.h — the other side of the external simulator protocol (runtime/sim/SimulatorProtocol.h): serves
// a program's in-process domain simulator to a client on a pair of streams, one JSON line per message.
//
// `cbtl simulator serve FILE` runs it on stdin/stdout. Its uses: a reference implementation of the protocol that
// every test can run against (Cooking over the protocol must give byte-identical results to Cooking in
// process), and the measure of what the protocol costs per step (bench/).
//
// A malformed request is answered with "ok": false and a reason; the server carries on. It ends at "bye" or at
// the end of its input.
#pragma once

#include "app/LoadedProgram.h"

#include <iosfwd>

namespace cbtl::app {

// Serves `program`'s in-process domain; returns 0 after "bye" or the end of input, 1 when the domain has no
// in-process simulator (the hello request is then refused with that reason).
int serveSimulator(const LoadedProgram& program, std::istream& in, std::ostream& out);

}  // namespace cbtl::app
