//! Child processes with a time limit, an address-space limit and bounded output capture.
//!
//! Every process the harnesses start (the `stochvib` binary, and the harness' own worker processes that
//! call the library) runs under `RLIMIT_AS` so that a hostile size read from a file (`2^60` samples, a
//! `/dev/zero` read to the end) fails inside the child instead of exhausting the shared machine's memory,
//! and is killed (`SIGKILL`) when its time is up.

use std::io::Read;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Address-space limit of the child processes, bytes.
pub const DEFAULT_MEMORY_LIMIT: u64 = 2 << 30;

/// Bytes of stdout/stderr kept per stream (the head; the rest is counted, not stored).
const KEEP: usize = 1 << 20;

/// How a child process ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Exit {
    /// Exited with this code.
    Code(i32),
    /// Killed by this signal (not by the harness).
    Signal(i32),
    /// Killed by the harness when its time was up.
    Timeout,
}

impl std::fmt::Display for Exit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Exit::Code(c) => write!(f, "exit {c}"),
            Exit::Signal(s) => write!(f, "signal {s} ({})", signal_name(*s)),
            Exit::Timeout => write!(f, "timeout"),
        }
    }
}

/// The usual name of a signal number on Linux.
pub fn signal_name(s: i32) -> &'static str {
    match s {
        libc::SIGSEGV => "SIGSEGV",
        libc::SIGABRT => "SIGABRT",
        libc::SIGBUS => "SIGBUS",
        libc::SIGILL => "SIGILL",
        libc::SIGFPE => "SIGFPE",
        libc::SIGKILL => "SIGKILL",
        libc::SIGTERM => "SIGTERM",
        libc::SIGTRAP => "SIGTRAP",
        _ => "other",
    }
}

/// What a finished child printed and how it ended.
#[derive(Debug, Clone)]
pub struct Output {
    /// How it ended.
    pub exit: Exit,
    /// Its stdout (first MiB, lossy UTF-8).
    pub stdout: String,
    /// Its stderr (first MiB, lossy UTF-8).
    pub stderr: String,
    /// Wall time.
    pub elapsed: Duration,
}

/// Puts the address-space limit on `cmd`'s process (applied between fork and exec).
pub fn limit_memory(cmd: &mut Command, bytes: u64) {
    // SAFETY: only async-signal-safe calls (setrlimit) run between fork and exec.
    unsafe {
        cmd.pre_exec(move || {
            let lim = libc::rlimit {
                rlim_cur: bytes as libc::rlim_t,
                rlim_max: bytes as libc::rlim_t,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            let core = libc::rlimit {
                rlim_cur: 0,
                rlim_max: 0,
            };
            libc::setrlimit(libc::RLIMIT_CORE, &core);
            Ok(())
        });
    }
}

fn drain(mut r: impl Read + Send + 'static) -> std::thread::JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut keep = Vec::new();
        let mut buf = [0u8; 65536];
        loop {
            match r.read(&mut buf) {
                Ok(0) | Err(_) => break,
                Ok(n) => {
                    let room = KEEP.saturating_sub(keep.len());
                    keep.extend_from_slice(&buf[..n.min(room)]);
                }
            }
        }
        keep
    })
}

/// Runs `cmd` (stdin closed) under `memory` bytes of address space, killing it after `timeout`.
///
/// # Panics
/// If the process cannot be started at all (a harness set-up error, not a finding).
pub fn run(mut cmd: Command, timeout: Duration, memory: u64) -> Output {
    limit_memory(&mut cmd, memory);
    cmd.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
    let start = Instant::now();
    let mut child: Child =
        stochvib::store::spawn_child(&mut cmd).unwrap_or_else(|e| panic!("cannot start {cmd:?}: {e}"));
    let out = drain(child.stdout.take().expect("piped stdout"));
    let err = drain(child.stderr.take().expect("piped stderr"));
    let exit = loop {
        match child.try_wait() {
            Ok(Some(st)) => {
                break match (st.code(), st.signal()) {
                    (Some(c), _) => Exit::Code(c),
                    (None, Some(s)) => Exit::Signal(s),
                    _ => Exit::Code(-1),
                }
            }
            Ok(None) if start.elapsed() >= timeout => {
                let _ = child.kill();
                let _ = child.wait();
                break Exit::Timeout;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(e) => panic!("waiting for {cmd:?}: {e}"),
        }
    };
    let elapsed = start.elapsed();
    let stdout = String::from_utf8_lossy(&out.join().unwrap_or_default()).into_owned();
    let stderr = String::from_utf8_lossy(&err.join().unwrap_or_default()).into_owned();
    Output {
        exit,
        stdout,
        stderr,
        elapsed,
    }
}

/// The last `n` characters of `s` (for crash messages).
pub fn tail(s: &str, n: usize) -> String {
    let c: Vec<char> = s.chars().collect();
    c[c.len().saturating_sub(n)..].iter().collect()
}
