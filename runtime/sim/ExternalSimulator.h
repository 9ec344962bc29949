// ExternalSimulator.h — a domain simulator that is another program: cbtl starts it and speaks the external
// simulator protocol with it (SimulatorProtocol.h) on its stdin and stdout, so a new domain needs no C++ and no
// rebuilt cbtl.
//
// Construction starts the program, greets it and checks its manifest against the program's schema: every
// mismatch is listed at once in one ExternalSimulatorError. Every answer is then checked against the schema
// (values by declared type, feedback events by declaration). Whatever goes wrong on the other side (it crashes,
// writes a line that is not the answer, says "ok": false, or does not answer within the timeout) is an
// ExternalSimulatorError that names the request, the line of the program's output and its last words on
// stderr; the program is then stopped, and the run ends — it never hangs and never continues on a guess.
//
// An evaluation twin is a second world in the same program (the "twin" request), so it shares the simulated
// user. The program is stopped when the last of its worlds is destroyed.
#pragma once

#include "runtime/core/Values.h"  // rt::RuntimeError
#include "runtime/sim/DomainSimulator.h"
#include "runtime/sim/ProtocolSchema.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::sim {

// Bad input: the simulator program or its answers (exit 1 in cbtl), never a bug of cbtl. `location` is where
// the command came from ("coffee.cbtl:9:1" for a `simulator` line; empty for --simulator).
struct ExternalSimulatorError : rt::RuntimeError {
  using rt::RuntimeError::RuntimeError;
};

struct ExternalSimulatorConfig {
  std::string command;           // run with /bin/sh -c
  std::string workingDirectory;  // empty: the current one
  std::string origin;            // "file:line:col" of the `simulator` line; empty: the command line
  int timeoutMs = 30000;         // for every answer, the greeting included
};

class Connection;

class ExternalSimulator : public DomainSimulator {
 public:
  // Starts the program, checks its manifest, and resets the training world with `seed`.
  ExternalSimulator(const ExternalSimulatorConfig& config, std::shared_ptr<const ProtocolSchema> schema,
                    const SimulatorOptions& options, std::uint64_t seed);
  ~ExternalSimulator() override;

  void reset(std::uint64_t seed) override;
  Observation observe() const override;
  StepResult act(const ActionCall& call) override;
  StepResult idle() override;
  std::string requestedTask() const override { return task_; }
  std::vector<std::string> judgedPreferences() const override;
  std::unique_ptr<DomainSimulator> makeEvaluationTwin() const override;

  // What the manifest check found that does not stop a run (e.g. a learned event the simulator never sends).
  const std::vector<std::string>& manifestWarnings() const;
  // The name the simulator gave itself in its manifest (its command when it gave none).
  const std::string& simulatorName() const;

 private:
  ExternalSimulator(std::shared_ptr<Connection> connection, int world);
  StepResult step(const char* op, const ActionCall* call);

  std::shared_ptr<Connection> connection_;
  int world_ = 0;
  std::string task_;
};

}  // namespace cbtl::sim
