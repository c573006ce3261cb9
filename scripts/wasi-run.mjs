// Runs a wasm32-wasip1 program (e.g. a `cargo test` binary) under node's WASI:
// `node scripts/wasi-run.mjs program.wasm [args…]`, exiting with its status.
// Cargo uses it as the runner of wasm32-wasip1 (CARGO_TARGET_WASM32_WASIP1_RUNNER).
// The current directory is preopened as `.` so the program can read relative paths.
import { readFile } from "node:fs/promises";
import { argv, env, exit } from "node:process";
import { WASI } from "node:wasi";

const [program, ...args] = argv.slice(2);
if (!program) {
  console.error("usage: node wasi-run.mjs program.wasm [args…]");
  exit(2);
}
const wasi = new WASI({
  version: "preview1",
  args: [program, ...args],
  env,
  preopens: { ".": "." },
  returnOnExit: true,
});
const module = await WebAssembly.compile(await readFile(program));
const instance = await WebAssembly.instantiate(module, wasi.getImportObject());
// A trap (e.g. a Rust panic, which aborts on wasm32-wasip1) throws here, and
// node exits non-zero with the error printed.
exit(wasi.start(instance));
