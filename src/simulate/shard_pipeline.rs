//! The pending shards of a run file realized by the thread pool in order while the calling thread writes
//! each shard as soon as all its realizations are done.
//!
//! Realized one shard at a time (a parallel loop over the shard's lockstep groups, then the write), the
//! threads idle at every shard's end: a shard of 50 realizations is 7 groups of at most 8, which 2 threads
//! share 4 : 3, and the write runs alone. Here the groups of every pending shard form one queue, taken in
//! order by the pool's threads (and by the calling thread itself when it is one of the pool's), at most
//! [`LOOKAHEAD`] shards ahead of the next shard to write; the calling thread writes the shards in order, each
//! when its groups are done, and reports progress then. So a thread that finishes the last groups of one
//! shard goes on with the next, progress comes shard by shard as before, a stop requested from the progress
//! callback (a panic that unwinds, as Ctrl-C in the Python package) waits only for the groups being
//! computed, and at most [`LOOKAHEAD`] shards of results are held. A realization's result depends only on
//! its own random stream, so the file is the same bit for bit.
//!
//! A job must not run rayon parallel loops inside: the threads wait on a condition variable when the
//! lookahead is full, and a thread that has stolen part of another job's parallel loop would then block
//! inside that loop's join (a deadlock seen with whole transient shards as jobs; those use
//! `transient::monte_carlo::write_while_computing`, which blocks no pool thread).

use crate::error::{Error, Result};
use std::sync::{Condvar, Mutex, MutexGuard};

/// Shards (the next one to write included) whose groups the threads may compute before that shard is
/// written.
pub(crate) const LOOKAHEAD: usize = 2;

/// The queue and its results, shared by the threads.
struct Shared<T> {
    /// (shard position, first realization, width) of every group, in order.
    jobs: Vec<(usize, u64, usize)>,
    state: Mutex<State<T>>,
    changed: Condvar,
}

struct State<T> {
    /// The next job to take.
    next: usize,
    /// The position of the next shard to write (the threads take jobs of shards below it + LOOKAHEAD).
    frontier: usize,
    /// Set when the run stops early (an error, a panic, a stop requested from the progress callback).
    stop: bool,
    done: Vec<Option<Result<Vec<T>>>>,
}

impl<T> Shared<T> {
    fn lock(&self) -> MutexGuard<'_, State<T>> {
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The next job within the lookahead, taken; None when there is none now (`wait`: until there is one,
    /// or none will come).
    fn take(&self, wait: bool) -> Option<usize> {
        let mut st = self.lock();
        loop {
            if st.stop || st.next >= self.jobs.len() {
                return None;
            }
            if self.jobs[st.next].0 < st.frontier + LOOKAHEAD {
                st.next += 1;
                return Some(st.next - 1);
            }
            if !wait {
                return None;
            }
            st = self.changed.wait(st).unwrap_or_else(|p| p.into_inner());
        }
    }

    fn put(&self, job: usize, r: Result<Vec<T>>) {
        self.lock().done[job] = Some(r);
        self.changed.notify_all();
    }

    fn stop(&self) {
        self.lock().stop = true;
        self.changed.notify_all();
    }
}

/// Stops the run when dropped by unwinding (a panic of a thread or of the progress callback), so that the
/// other threads take no more jobs and a waiting caller wakes.
struct StopOnUnwind<'a, T>(&'a Shared<T>);

impl<T> Drop for StopOnUnwind<'_, T> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.stop();
        }
    }
}

/// Realizes the groups `groups(s)` of each shard s of `shards` (in order; each group (first, width) gives
/// its `width` results through `realize`) on the current rayon pool, and calls `write(s, results)` on the
/// calling thread for each shard, in order, with its results in realization order, as soon as they are all
/// done (see the module docs). `init` makes the working memory of each thread.
///
/// # Errors
/// The first error of a shard's groups (in group order) when that shard's turn to be written comes, or of
/// `write`; the threads then take no more groups.
pub(crate) fn realize_and_write<T, S>(
    shards: &[usize],
    groups: impl Fn(usize) -> Vec<(u64, usize)>,
    init: impl Fn() -> S + Sync,
    realize: impl Fn(&mut S, u64, usize) -> Result<Vec<T>> + Sync,
    mut write: impl FnMut(usize, Vec<T>) -> Result<()>,
) -> Result<()>
where
    T: Send,
{
    let jobs: Vec<(usize, u64, usize)> = shards
        .iter()
        .enumerate()
        .flat_map(|(pos, &s)| groups(s).into_iter().map(move |(a, w)| (pos, a, w)))
        .collect();
    let shared = Shared {
        state: Mutex::new(State {
            next: 0,
            frontier: 0,
            stop: false,
            done: (0..jobs.len()).map(|_| None).collect(),
        }),
        jobs,
        changed: Condvar::new(),
    };
    // the calling thread computes too when it is one of the pool's threads (inside `install`)
    let caller_works = rayon::current_thread_index().is_some();
    let helpers = rayon::current_num_threads().saturating_sub(usize::from(caller_works));
    let compute = |s: &mut Option<S>, job: usize| {
        let (_, a, w) = shared.jobs[job];
        let r = realize(s.get_or_insert_with(&init), a, w);
        shared.put(job, r);
    };
    rayon::in_place_scope(|scope| {
        let _stop = StopOnUnwind(&shared);
        for _ in 0..helpers {
            scope.spawn(|_| {
                let _stop = StopOnUnwind(&shared);
                let mut s = None;
                while let Some(job) = shared.take(true) {
                    compute(&mut s, job);
                }
            });
        }
        let result = write_in_order(&shared, shards, caller_works, &compute, &mut write);
        if result.is_err() {
            shared.stop();
        }
        result
    })
}

/// The calling thread's part of [`realize_and_write`]: each shard written when its groups are done, jobs
/// computed meanwhile when `works`, else a wait for the threads.
fn write_in_order<T, S>(
    shared: &Shared<T>,
    shards: &[usize],
    works: bool,
    compute: &impl Fn(&mut Option<S>, usize),
    write: &mut impl FnMut(usize, Vec<T>) -> Result<()>,
) -> Result<()> {
    let mut s = None;
    let mut first = 0;
    for (pos, &shard) in shards.iter().enumerate() {
        let end = first + shared.jobs[first..].iter().take_while(|j| j.0 == pos).count();
        let results = loop {
            let mut st = shared.lock();
            if st.done[first..end].iter().all(Option::is_some) {
                let results: Vec<_> = st.done[first..end].iter_mut().filter_map(Option::take).collect();
                st.frontier = pos + 1;
                drop(st);
                shared.changed.notify_all();
                break results;
            }
            if st.stop {
                return Err(Error::invalid("run", shard, "stopped: a thread of the run panicked"));
            }
            drop(st);
            match works.then(|| shared.take(false)).flatten() {
                Some(job) => compute(&mut s, job),
                None => {
                    let st = shared.lock();
                    if st.done[first..end].iter().all(Option::is_some) || st.stop {
                        continue;
                    }
                    // woken by a group done (or a stop); the lookahead may have room again after a write
                    drop(shared.changed.wait(st).unwrap_or_else(|p| p.into_inner()));
                }
            }
        };
        let mut all = Vec::new();
        for r in results {
            all.extend(r?);
        }
        write(shard, all)?;
        first = end;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::realize_and_write;
    use crate::error::{Error, Result};
    use std::sync::Mutex;

    /// Shards of 5, 0, 13 and 2 "realizations" (the result of realization i is i²) in groups of at most 4,
    /// on pools of 1, 2 and 3 threads, called inside and outside the pool: every shard written once, in
    /// order, with its results in realization order.
    #[test]
    fn shards_are_written_in_order_with_their_results() {
        let sizes = [5u64, 0, 13, 2];
        let starts: Vec<u64> = sizes
            .iter()
            .scan(0, |a, &n| Some(std::mem::replace(a, *a + n)))
            .collect();
        let groups = |s: usize| -> Vec<(u64, usize)> {
            let (a, n) = (starts[s], sizes[s]);
            (a..a + n)
                .step_by(4)
                .map(|g| (g, 4.min((a + n - g) as usize)))
                .collect()
        };
        let realize =
            |_: &mut (), a: u64, w: usize| -> Result<Vec<u64>> { Ok((a..a + w as u64).map(|i| i * i).collect()) };
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            for inside in [true, false] {
                let written = Mutex::new(Vec::new());
                let run = || {
                    realize_and_write(
                        &[0, 1, 2, 3],
                        groups,
                        || (),
                        realize,
                        |s, r| {
                            written.lock().unwrap().push((s, r));
                            Ok(())
                        },
                    )
                };
                if inside { pool.install(run) } else { run() }.unwrap();
                let want: Vec<(usize, Vec<u64>)> = (0..4)
                    .map(|s| (s, (starts[s]..starts[s] + sizes[s]).map(|i| i * i).collect()))
                    .collect();
                assert_eq!(
                    *written.lock().unwrap(),
                    want,
                    "{threads} threads, inside the pool: {inside}"
                );
            }
        }
    }

    /// A group's error is returned when its shard's turn comes (the shards before it written), a write's
    /// error at once, and a panic of the write callback unwinds out of the call after the threads stop.
    #[test]
    fn errors_and_a_stop_end_the_run_after_the_shards_before_them() {
        type Realize<'a> = &'a (dyn Fn(&mut (), u64, usize) -> Result<Vec<u64>> + Sync);
        type Write<'a> = &'a mut (dyn FnMut(usize, Vec<u64>) -> Result<()> + Send);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        // four shards of 2 realizations, one group each
        let four = |realize: Realize, write: Write| {
            pool.install(|| realize_and_write(&[0, 1, 2, 3], |s| vec![(s as u64 * 2, 2)], || (), realize, write))
        };
        let failing = |_: &mut (), a: u64, _: usize| -> Result<Vec<u64>> {
            if a == 4 {
                Err(Error::invalid("realization", a, "test"))
            } else {
                Ok(vec![a, a + 1])
            }
        };
        let mut written = Vec::new();
        let r = four(&failing, &mut |s, _| {
            written.push(s);
            Ok(())
        });
        assert!(r.unwrap_err().to_string().contains("test"));
        assert_eq!(written, vec![0, 1]);
        let ok = |_: &mut (), a: u64, _: usize| -> Result<Vec<u64>> { Ok(vec![a, a + 1]) };
        let r = four(&ok, &mut |s, _| match s {
            1 => Err(Error::invalid("shard", s, "write failed")),
            _ => Ok(()),
        });
        assert!(r.unwrap_err().to_string().contains("write failed"));
        let stopped = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            four(&ok, &mut |s, _| {
                assert!(s < 2, "stop requested");
                Ok(())
            })
        }));
        assert!(stopped.is_err());
    }
}
