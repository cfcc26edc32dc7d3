//! Typesetting in a child process, so that a formula that computes too much can really be
//! stopped: a thread cannot be killed from outside, a process can, and the kernel frees all it
//! allocated. The child is `lectern` itself, re-executed with the hidden `typeset-worker`
//! subcommand; it talks [`super::wire`] frames over stdin/stdout.
//!
//! Bounds: the child lowers its own address-space limit (`RLIMIT_AS`) to what it uses once
//! warmed up plus [`Bounds::memory_mb`], so an allocation beyond that fails and the child
//! aborts; the parent kills it when a formula runs past [`Bounds::time`]. Either way the parent
//! reports the formula and starts a fresh child for the next one.

use std::io::{BufReader, BufWriter, Read};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use super::typeset::{MathError, RenderedFormula, render_formula};
use super::wire::{self, Answer, Request};

/// The hidden subcommand that turns `lectern` into a typesetting worker.
pub const SUBCOMMAND: &str = "typeset-worker";

/// Stack for the thread that typesets: Typst recurses on nested input, and a deep formula must
/// end in Typst's own error, not a stack overflow.
pub(crate) const TYPESET_STACK_BYTES: usize = 256 << 20;

/// How long a fresh worker may take to start and load its fonts before it counts as broken.
const START_TIMEOUT: Duration = Duration::from_secs(20);

/// What one formula may cost.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bounds {
    /// Wall-clock time for typesetting and rasterising one formula.
    pub time: Duration,
    /// Memory one formula may allocate beyond the worker's own (fonts, code), in MiB.
    pub memory_mb: u64,
}

impl Default for Bounds {
    fn default() -> Self {
        Self {
            time: Duration::from_secs(2),
            memory_mb: 512,
        }
    }
}

impl Bounds {
    /// "formula stopped after 2 s …", the message for a formula over the time budget.
    pub fn time_error(&self) -> MathError {
        MathError {
            message: format!(
                "formula stopped after {} (it computes too much to typeset in time)",
                secs(self.time)
            ),
            col: None,
        }
    }

    /// "formula used more than 512 MB …", the message for a formula over the memory bound.
    pub fn memory_error(&self) -> MathError {
        MathError {
            message: format!(
                "formula used more than {} MB of memory and was stopped",
                self.memory_mb
            ),
            col: None,
        }
    }
}

fn secs(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s.fract() == 0.0 {
        format!("{s:.0} s")
    } else {
        format!("{s:.1} s")
    }
}

/// The child's side: typesets requests from stdin until it closes. `memory_mb` as in
/// [`Bounds`]. Returns the process exit code.
pub fn serve(memory_mb: u64) -> i32 {
    let work = std::thread::Builder::new()
        .name("typeset".into())
        .stack_size(TYPESET_STACK_BYTES)
        .spawn(move || serve_on_this_thread(memory_mb));
    match work.map(JoinHandle::join) {
        Ok(Ok(Ok(()))) => 0,
        Ok(Ok(Err(e))) => {
            eprintln!("lectern typeset-worker: {e}");
            1
        }
        _ => 2,
    }
}

fn serve_on_this_thread(memory_mb: u64) -> std::io::Result<()> {
    // Background work: never take the CPU from the lecturer's window.
    #[cfg(unix)]
    unsafe {
        libc::setpriority(libc::PRIO_PROCESS, 0, 5);
    }
    // If lectern goes (closed, crashed), a formula still computing goes with it instead of
    // running on to its memory bound with nobody left to kill it at its time budget.
    #[cfg(target_os = "linux")]
    unsafe {
        libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL as libc::c_ulong);
    }
    // Load fonts and warm Typst's caches before the limit, so it bounds the formula's own use.
    let _ = render_formula("x", super::MathSyntax::Typst, 20.0, [0, 0, 0, 255]);
    limit_address_space(memory_mb);
    let mut input = BufReader::new(std::io::stdin().lock());
    let mut output = BufWriter::new(std::io::stdout().lock());
    wire::write_answer(&mut output, &Answer::Ready(wire::VERSION.into()))?;
    while let Some(req) = wire::read_request(&mut input)? {
        let result = std::panic::catch_unwind(|| req.render()).unwrap_or_else(|_| {
            Err(MathError {
                message: "the typesetter failed on this formula (internal error)".into(),
                col: None,
            })
        });
        wire::write_answer(&mut output, &Answer::Done(result))?;
    }
    Ok(())
}

/// Lowers `RLIMIT_AS` to the current address space plus `memory_mb` MiB.
fn limit_address_space(memory_mb: u64) {
    #[cfg(target_os = "linux")]
    {
        let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) }.max(4096) as u64;
        let vsize = std::fs::read_to_string("/proc/self/statm")
            .ok()
            .and_then(|s| s.split_whitespace().next()?.parse::<u64>().ok())
            .map_or(0, |pages| pages * page);
        let limit = vsize + (memory_mb << 20);
        let rl = libc::rlimit {
            rlim_cur: limit as libc::rlim_t,
            rlim_max: limit as libc::rlim_t,
        };
        if unsafe { libc::setrlimit(libc::RLIMIT_AS, &rl) } != 0 {
            eprintln!(
                "lectern typeset-worker: cannot limit memory: {}",
                std::io::Error::last_os_error()
            );
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = memory_mb;
}

/// Why a worker gave no answer for a formula.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// It ran past the time budget and was killed.
    TimedOut,
    /// It hit the memory bound and died.
    OutOfMemory,
    /// It died some other way (the last lines it printed).
    Crashed(String),
}

/// The parent's side: one running worker process.
pub struct WorkerProcess {
    child: Child,
    stdin: BufWriter<ChildStdin>,
    answers: Receiver<std::io::Result<Answer>>,
    stderr: Arc<Mutex<Vec<u8>>>,
    stderr_reader: Option<JoinHandle<()>>,
}

impl WorkerProcess {
    /// Starts `program typeset-worker` and waits until it has loaded its fonts.
    pub fn start(program: &Path, bounds: &Bounds) -> Result<Self, String> {
        let mut child = Command::new(program)
            .arg(SUBCOMMAND)
            .arg("--memory-mb")
            .arg(bounds.memory_mb.to_string())
            // fewer malloc arenas: less address space reserved per thread under the limit
            .env("MALLOC_ARENA_MAX", "2")
            .env("RUST_LOG", "error")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("cannot start {}: {e}", program.display()))?;
        let stdin = BufWriter::new(child.stdin.take().expect("piped stdin"));
        let mut stdout = BufReader::new(child.stdout.take().expect("piped stdout"));
        let mut stderr_pipe = child.stderr.take().expect("piped stderr");
        let (tx, answers) = channel();
        std::thread::Builder::new()
            .name("typeset-answers".into())
            .spawn(move || {
                loop {
                    match wire::read_answer(&mut stdout) {
                        Ok(Some(a)) => {
                            if tx.send(Ok(a)).is_err() {
                                break;
                            }
                        }
                        Ok(None) => break,
                        Err(e) => {
                            let _ = tx.send(Err(e));
                            break;
                        }
                    }
                }
            })
            .map_err(|e| e.to_string())?;
        let stderr = Arc::new(Mutex::new(Vec::new()));
        let sink = stderr.clone();
        let stderr_reader = std::thread::Builder::new()
            .name("typeset-stderr".into())
            .spawn(move || {
                let mut buf = [0u8; 1024];
                while let Ok(n) = stderr_pipe.read(&mut buf) {
                    if n == 0 {
                        break;
                    }
                    if let Ok(mut s) = sink.lock() {
                        s.extend_from_slice(&buf[..n]);
                        // keep the tail: it says why the worker died
                        let excess = s.len().saturating_sub(8192);
                        s.drain(..excess);
                    }
                }
            })
            .ok();
        let mut worker = Self {
            child,
            stdin,
            answers,
            stderr,
            stderr_reader,
        };
        match worker.answers.recv_timeout(START_TIMEOUT) {
            Ok(Ok(Answer::Ready(v))) if v == wire::VERSION => Ok(worker),
            Ok(Ok(Answer::Ready(v))) => Err(format!(
                "{} speaks {v}, not {} (a stale build?)",
                program.display(),
                wire::VERSION
            )),
            Ok(Ok(_)) => Err("the worker answered before it was asked".into()),
            Ok(Err(e)) => Err(e.to_string()),
            Err(_) => {
                let why = worker.death_note();
                Err(format!("{} did not start: {why}", program.display()))
            }
        }
    }

    /// Typesets one formula, killing the worker if it runs past `bounds.time`. After an
    /// `Err`, the worker is gone: drop it and start another.
    pub fn typeset(
        &mut self,
        req: &Request,
        bounds: &Bounds,
    ) -> Result<Result<RenderedFormula, MathError>, Failure> {
        if let Err(e) = wire::write_request(&mut self.stdin, req) {
            return Err(Failure::Crashed(format!(
                "cannot send the formula: {e}; {}",
                self.death_note()
            )));
        }
        match self.answers.recv_timeout(bounds.time) {
            Ok(Ok(Answer::Done(result))) => Ok(result),
            Ok(Ok(Answer::Ready(_))) => Err(Failure::Crashed("unexpected answer".into())),
            Ok(Err(e)) => Err(Failure::Crashed(e.to_string())),
            Err(RecvTimeoutError::Timeout) => {
                self.kill();
                Err(Failure::TimedOut)
            }
            Err(RecvTimeoutError::Disconnected) => {
                let note = self.death_note();
                if note.contains("memory allocation of") || note.contains("out of memory") {
                    Err(Failure::OutOfMemory)
                } else {
                    Err(Failure::Crashed(note))
                }
            }
        }
    }

    fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// After the worker died: its exit status and the last line it printed.
    fn death_note(&mut self) -> String {
        self.kill();
        let status = self.child.try_wait().ok().flatten();
        if let Some(h) = self.stderr_reader.take() {
            let _ = h.join();
        }
        let tail = self
            .stderr
            .lock()
            .map(|s| String::from_utf8_lossy(&s).into_owned())
            .unwrap_or_default();
        let last = tail
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .unwrap_or("")
            .trim()
            .to_owned();
        let mut note = match status {
            Some(s) => format!("worker exited ({s})"),
            None => "worker gone".to_owned(),
        };
        if !last.is_empty() {
            note.push_str(": ");
            note.push_str(&last);
        }
        if tail.contains("memory allocation of") {
            note.push_str(" (out of memory)");
        }
        note
    }

    /// The worker's process id (for tests that look at its memory).
    pub fn pid(&self) -> u32 {
        self.child.id()
    }
}

impl Drop for WorkerProcess {
    fn drop(&mut self) {
        self.kill();
    }
}
