//! The typesetting pool: a queue of formulas and two worker threads, each driving one worker
//! process ([`super::worker`]). The window submits and polls (it never waits); `lectern
//! check`, `lectern export` and snapshot tests submit and wait. Either way each formula is
//! bounded by [`Bounds`].
//!
//! Order: formulas on screen ("urgent") first, newest request first (the slide the lecturer
//! just paged to beats one they paged past); then formulas typeset ahead, in the order asked.
//! A job nobody asked for again within [`EXPIRE`] is dropped unstarted (a window resize leaves
//! many sizes behind); whoever still wants it submits it again.
//!
//! Where no worker process can start (a unit-test binary, a missing executable), formulas are
//! typeset on a thread of this process instead: still bounded in time for whoever waits (the
//! answer is "stopped after 2 s" and the thread is left to finish on its own), but not in memory.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::sync::{Arc, Condvar, Mutex, OnceLock};
use std::time::{Duration, Instant};

pub use super::formula::{Notify, Poll};
use super::typeset::{MathError, RenderedFormula};
use super::wire::Request;
use super::worker::{Bounds, Failure, TYPESET_STACK_BYTES, WorkerProcess};

/// Unstarted jobs not asked for again within this long are dropped.
pub const EXPIRE: Duration = Duration::from_secs(10);

/// Worker threads (each with its own process). Two: one formula that runs to its time budget
/// does not hold up the others, and the workers run at low priority beside the window.
const WORKERS: usize = 2;

/// One formula asked for: its request and, once done, its result.
pub struct Job {
    pub req: Request,
    inner: Mutex<JobInner>,
    done: Condvar,
}

struct JobInner {
    state: State,
    urgent: bool,
    /// Never expires (someone waits for it).
    keep: bool,
    wanted_at: Instant,
    notify: Option<Notify>,
}

enum State {
    Queued,
    Running,
    Done(Result<RenderedFormula, MathError>),
    Expired,
}

impl Job {
    pub fn poll(&self) -> Poll {
        let inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        match &inner.state {
            State::Queued | State::Running => Poll::Pending,
            State::Done(r) => Poll::Done(r.clone()),
            State::Expired => Poll::Expired,
        }
    }

    /// Asks for the job again: keeps it from expiring; `urgent` moves it ahead of formulas
    /// typeset ahead, `notify` runs when it is done (e.g. a repaint).
    pub fn want(&self, urgent: bool, notify: Option<Notify>) {
        let mut inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        inner.wanted_at = Instant::now();
        inner.urgent |= urgent;
        if notify.is_some() {
            inner.notify = notify;
        }
    }

    /// Blocks until the job is done. Workers answer within the time budget (plus starting a
    /// worker); the extra margin only guards against a bug leaving the caller stuck forever.
    pub fn wait(&self) -> Result<RenderedFormula, MathError> {
        let bounds = pool().bounds();
        let give_up = Instant::now() + bounds.time * 4 + Duration::from_secs(60);
        let mut inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        inner.keep = true;
        loop {
            match &inner.state {
                State::Done(r) => return r.clone(),
                State::Expired => {
                    return Err(MathError {
                        message: "formula dropped before it was typeset".into(),
                        col: None,
                    });
                }
                State::Queued | State::Running => {}
            }
            let now = Instant::now();
            if now >= give_up {
                return Err(bounds.time_error());
            }
            inner = self
                .done
                .wait_timeout(inner, give_up - now)
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
    }

    fn finish(&self, result: Result<RenderedFormula, MathError>) {
        let notify = {
            let mut inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
            inner.state = State::Done(result);
            inner.notify.take()
        };
        self.done.notify_all();
        if let Some(n) = notify {
            n();
        }
    }
}

/// Timings of the pool's work, for reports and benchmarks.
#[derive(Debug, Default, Clone, Copy)]
pub struct Stats {
    pub done: u64,
    pub timed_out: u64,
    pub out_of_memory: u64,
    pub workers_started: u64,
    /// Wall time from picking a job to its result, summed (µs).
    pub busy_us: u64,
}

/// Where to find the worker executable: unset means "find it" (this executable if it is
/// `lectern`), `Some(None)` means "no process, typeset in this one".
static PROGRAM: Mutex<Option<Option<PathBuf>>> = Mutex::new(None);

/// Uses `program` (e.g. `env!("CARGO_BIN_EXE_lectern")` in integration tests) as the
/// typesetting worker; `None` typesets in this process (no memory bound).
pub fn set_worker_program(program: Option<PathBuf>) {
    *PROGRAM.lock().unwrap_or_else(|e| e.into_inner()) = Some(program);
}

/// The worker executable: as set, else `LECTERN_TYPESET_WORKER`, else this executable when it
/// is `lectern` (a test binary is not, and then formulas are typeset in-process).
pub fn worker_program() -> Option<PathBuf> {
    if let Some(set) = PROGRAM.lock().unwrap_or_else(|e| e.into_inner()).clone() {
        return set;
    }
    if let Some(p) = std::env::var_os("LECTERN_TYPESET_WORKER") {
        return (!p.is_empty()).then(|| p.into());
    }
    let exe = std::env::current_exe().ok()?;
    (exe.file_stem()? == "lectern").then_some(exe)
}

/// Every formula asked for while recording (see [`record_requests`]).
static RECORDED: Mutex<Option<Vec<Request>>> = Mutex::new(None);

/// From now on, remember every formula asked for (`lectern export --web` typesets exactly
/// those the slides asked for into the page).
pub fn record_requests() {
    let mut r = RECORDED.lock().unwrap_or_else(|e| e.into_inner());
    r.get_or_insert_with(Vec::new);
}

/// The formulas asked for since [`record_requests`] (and since the last call).
pub fn take_recorded() -> Vec<Request> {
    let mut r = RECORDED.lock().unwrap_or_else(|e| e.into_inner());
    r.as_mut().map(std::mem::take).unwrap_or_default()
}

pub struct Pool {
    queue: Mutex<Vec<Arc<Job>>>,
    /// Jobs being typeset now.
    running: AtomicUsize,
    ready: Condvar,
    bounds: Mutex<Bounds>,
    stats: Mutex<Stats>,
    started: OnceLock<()>,
}

/// The process-wide pool.
pub fn pool() -> &'static Pool {
    static POOL: OnceLock<Pool> = OnceLock::new();
    POOL.get_or_init(|| Pool {
        queue: Mutex::new(Vec::new()),
        running: AtomicUsize::new(0),
        ready: Condvar::new(),
        bounds: Mutex::new(Bounds::default()),
        stats: Mutex::new(Stats::default()),
        started: OnceLock::new(),
    })
}

impl Pool {
    pub fn bounds(&self) -> Bounds {
        *self.bounds.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Changes the bounds for formulas started from now on (running workers keep their memory
    /// bound until they are restarted).
    pub fn set_bounds(&self, bounds: Bounds) {
        *self.bounds.lock().unwrap_or_else(|e| e.into_inner()) = bounds;
    }

    /// Formulas queued or being typeset.
    pub fn busy(&self) -> usize {
        let queued = self.queue.lock().map_or(0, |q| q.len());
        queued + self.running.load(Ordering::Relaxed)
    }

    pub fn stats(&self) -> Stats {
        *self.stats.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Queues a formula. `keep`: never expires (the caller will [`Job::wait`]).
    pub fn submit(
        &'static self,
        req: Request,
        urgent: bool,
        keep: bool,
        notify: Option<Notify>,
    ) -> Arc<Job> {
        if let Some(seen) = RECORDED.lock().unwrap_or_else(|e| e.into_inner()).as_mut() {
            seen.push(req.clone());
        }
        self.started.get_or_init(|| {
            for i in 0..WORKERS {
                let _ = std::thread::Builder::new()
                    .name(format!("typeset-pool-{i}"))
                    .spawn(move || self.work());
            }
        });
        let job = Arc::new(Job {
            req,
            inner: Mutex::new(JobInner {
                state: State::Queued,
                urgent,
                keep,
                wanted_at: Instant::now(),
                notify,
            }),
            done: Condvar::new(),
        });
        self.queue
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(job.clone());
        self.ready.notify_one();
        job
    }

    /// Typesets one formula within the bounds, waiting for it.
    pub fn typeset(&'static self, req: Request) -> Result<RenderedFormula, MathError> {
        self.submit(req, true, true, None).wait()
    }

    /// The next job to run, waiting for one.
    fn next_job(&self) -> Arc<Job> {
        let mut queue = self.queue.lock().unwrap_or_else(|e| e.into_inner());
        loop {
            if let Some(job) = pick(&mut queue) {
                self.running.fetch_add(1, Ordering::Relaxed);
                return job;
            }
            queue = self
                .ready
                .wait_timeout(queue, EXPIRE)
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
    }

    /// One worker thread: runs jobs through its own worker process, restarting it after a
    /// kill, or in this process when none can start.
    fn work(&self) {
        let mut process: Option<WorkerProcess> = None;
        let mut warned = false;
        loop {
            let job = self.next_job();
            let bounds = self.bounds();
            let start = Instant::now();
            if process.is_none()
                && let Some(program) = worker_program()
            {
                match WorkerProcess::start(&program, &bounds) {
                    Ok(p) => {
                        process = Some(p);
                        self.count(|s| s.workers_started += 1);
                    }
                    Err(e) if !warned => {
                        tracing::warn!("typesetting in-process (no memory bound): {e}");
                        warned = true;
                    }
                    Err(_) => {}
                }
            }
            let started = Instant::now();
            let result = match process.as_mut() {
                Some(p) => match p.typeset(&job.req, &bounds) {
                    Ok(r) => r,
                    Err(failure) => {
                        process = None;
                        match failure {
                            Failure::TimedOut => {
                                self.count(|s| s.timed_out += 1);
                                Err(bounds.time_error())
                            }
                            Failure::OutOfMemory => {
                                self.count(|s| s.out_of_memory += 1);
                                Err(bounds.memory_error())
                            }
                            Failure::Crashed(why) => Err(crash_error(&why, started, &bounds)),
                        }
                    }
                },
                None => {
                    let r = in_process(&job.req, &bounds);
                    if r.as_ref().is_err_and(|e| *e == bounds.time_error()) {
                        self.count(|s| s.timed_out += 1);
                    }
                    r
                }
            };
            let us = start.elapsed().as_micros() as u64;
            self.count(|s| {
                s.done += 1;
                s.busy_us += us;
            });
            job.finish(result);
            self.running.fetch_sub(1, Ordering::Relaxed);
        }
    }

    fn count(&self, f: impl FnOnce(&mut Stats)) {
        f(&mut self.stats.lock().unwrap_or_else(|e| e.into_inner()));
    }
}

/// Typesets on a fresh thread of this process, waiting at most the time budget.
fn in_process(req: &Request, bounds: &Bounds) -> Result<RenderedFormula, MathError> {
    let (tx, rx) = channel();
    let req = req.clone();
    let spawned = std::thread::Builder::new()
        .name("typeset-inline".into())
        .stack_size(TYPESET_STACK_BYTES)
        .spawn(move || {
            let r = std::panic::catch_unwind(|| req.render());
            // the waiter may have given up on us: nobody to tell
            let _ = tx.send(r);
        });
    if let Err(e) = spawned {
        return Err(MathError {
            message: format!("cannot typeset: {e}"),
            col: None,
        });
    }
    match rx.recv_timeout(bounds.time) {
        Ok(Ok(r)) => r,
        Ok(Err(_)) => Err(MathError {
            message: "the typesetter failed on this formula (internal error)".into(),
            col: None,
        }),
        Err(RecvTimeoutError::Timeout) => Err(bounds.time_error()),
        Err(RecvTimeoutError::Disconnected) => Err(MathError {
            message: "the typesetter stopped unexpectedly".into(),
            col: None,
        }),
    }
}

/// Takes the next job to run from `queue` (marking it running): urgent first, the newest
/// request first among those; else first come. Drops jobs nobody holds any more, and expires
/// unwanted ones.
fn pick(queue: &mut Vec<Arc<Job>>) -> Option<Arc<Job>> {
    queue.retain(|job| {
        if Arc::strong_count(job) == 1 {
            return false;
        }
        let mut inner = job.inner.lock().unwrap_or_else(|e| e.into_inner());
        if !inner.keep && inner.wanted_at.elapsed() > EXPIRE {
            inner.state = State::Expired;
            drop(inner);
            job.done.notify_all();
            return false;
        }
        true
    });
    let key = |job: &Arc<Job>| {
        let inner = job.inner.lock().unwrap_or_else(|e| e.into_inner());
        (inner.urgent, inner.wanted_at)
    };
    let mut best: Option<(usize, (bool, Instant))> = None;
    for (i, job) in queue.iter().enumerate() {
        let k = key(job);
        let better = match best {
            None => true,
            // urgent beats not urgent; among urgent, the newer request wins
            Some((_, (bu, bt))) => k.0 && (!bu || k.1 > bt),
        };
        if better {
            best = Some((i, k));
        }
    }
    let job = queue.remove(best?.0);
    job.inner.lock().unwrap_or_else(|e| e.into_inner()).state = State::Running;
    Some(job)
}

/// A worker that died of something other than the bounds (e.g. a stack overflow on absurdly
/// deep nesting): still an error at the formula, never a hang.
fn crash_error(why: &str, started: Instant, bounds: &Bounds) -> MathError {
    let message = if why.contains("overflowed its stack") {
        "formula nested too deeply to typeset".to_owned()
    } else if started.elapsed() >= bounds.time {
        return bounds.time_error();
    } else {
        format!("the typesetter stopped on this formula ({why})")
    };
    MathError { message, col: None }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::MathSyntax;

    fn req(src: &str) -> Request {
        Request {
            src: src.into(),
            syntax: MathSyntax::Typst,
            style: Default::default(),
            size_px: 30.0,
            rgba: [0, 0, 0, 255],
        }
    }

    /// Where no worker process can start, the caller still gets an answer at the budget.
    #[test]
    fn in_process_typesetting_answers_within_the_time_budget() {
        let bounds = Bounds {
            time: Duration::from_millis(200),
            memory_mb: 64,
        };
        let t = Instant::now();
        let r = in_process(&req("#range(400000).map(i => i).len()"), &bounds);
        assert_eq!(r.unwrap_err(), bounds.time_error());
        assert!(t.elapsed() < Duration::from_secs(2), "{:?}", t.elapsed());
        assert!(in_process(&req("x^2"), &Bounds::default()).is_ok());
    }

    #[test]
    fn urgent_newest_jobs_go_first_and_unwanted_ones_expire() {
        // a private queue, through the pool's picking rule
        let mk = |urgent: bool, age_ms: u64| {
            Arc::new(Job {
                req: req("x"),
                inner: Mutex::new(JobInner {
                    state: State::Queued,
                    urgent,
                    keep: false,
                    wanted_at: Instant::now() - Duration::from_millis(age_ms),
                    notify: None,
                }),
                done: Condvar::new(),
            })
        };
        let (ahead, old_urgent, new_urgent, stale) = (
            mk(false, 0),
            mk(true, 500),
            mk(true, 100),
            mk(false, 60_000),
        );
        let mut queue = vec![
            ahead.clone(),
            old_urgent.clone(),
            new_urgent.clone(),
            stale.clone(),
        ];
        let order: Vec<_> = std::iter::from_fn(|| pick(&mut queue))
            .map(|j| Arc::as_ptr(&j))
            .collect();
        assert_eq!(
            order,
            vec![
                Arc::as_ptr(&new_urgent),
                Arc::as_ptr(&old_urgent),
                Arc::as_ptr(&ahead)
            ]
        );
        assert_eq!(stale.poll(), Poll::Expired);
    }
}
