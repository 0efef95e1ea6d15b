//! Slices of a batch's sweep: `--shard K/N` runs the runs whose index i
//! (from 0) has `i mod N = K - 1`, so N processes, on one machine or many,
//! share a sweep without talking to each other and `elcon merge` joins
//! their tables. `--shard auto` takes K and N from the scheduler that
//! started the process: a SLURM job array (`SLURM_ARRAY_TASK_ID` with
//! `SLURM_ARRAY_TASK_COUNT`, or `SLURM_ARRAY_TASK_MIN`/`_MAX`, and
//! `SLURM_ARRAY_TASK_STEP`), or a Kubernetes indexed Job
//! (`JOB_COMPLETION_INDEX`, from 0, with the count in `ELCON_SHARD_COUNT`,
//! the Job's `completions`). docs/scenes.md has a script for each.

/// The K-th of N slices of a sweep (1-based K).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, from 1.
    pub index: usize,
    /// N.
    pub count: usize,
}

/// The variable that gives N beside a Kubernetes indexed Job's
/// `JOB_COMPLETION_INDEX` (set it to the Job's `completions`).
pub const SHARD_COUNT_VARIABLE: &str = "ELCON_SHARD_COUNT";

impl std::str::FromStr for Shard {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| format!("`{s}`: a shard is K/N, e.g. 2/8, or auto"))?;
        let index: usize = k
            .trim()
            .parse()
            .map_err(|_| format!("`{s}`: K must be a whole number"))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| format!("`{s}`: N must be a whole number"))?;
        Self::new(index, count).map_err(|e| format!("`{s}`: {e}"))
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// Shard K of N.
    ///
    /// # Errors
    /// Unless 1 <= K <= N.
    pub fn new(index: usize, count: usize) -> Result<Self, String> {
        if count == 0 || index == 0 || index > count {
            return Err(format!("need 1 <= K <= N, got K = {index}, N = {count}"));
        }
        Ok(Self { index, count })
    }

    /// Whether run `i` (from 0) belongs to this shard.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }

    /// How many of `total` runs (indices 0..total) belong to this shard.
    pub fn len_of(&self, total: usize) -> usize {
        let first = self.index - 1;
        if total <= first {
            0
        } else {
            (total - first).div_ceil(self.count)
        }
    }

    /// The index of this shard's j-th run.
    pub fn nth(&self, j: usize) -> usize {
        self.index - 1 + j * self.count
    }

    /// The shard of this process from its scheduler's variables, read
    /// through `var` (`std::env::var` in the command line; tests pass a
    /// table): SLURM's job array first, then a Kubernetes indexed Job.
    ///
    /// # Errors
    /// A message naming the variables when none is set or they disagree.
    pub fn from_scheduler(var: impl Fn(&str) -> Option<String>) -> Result<Self, String> {
        let number = |name: &str| -> Result<Option<usize>, String> {
            match var(name) {
                None => Ok(None),
                Some(v) => v
                    .trim()
                    .parse()
                    .map(Some)
                    .map_err(|_| format!("{name}={v}: not a whole number")),
            }
        };
        if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let step = number("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
            let count = match (
                number("SLURM_ARRAY_TASK_COUNT")?,
                number("SLURM_ARRAY_TASK_MAX")?,
            ) {
                (Some(c), _) => c,
                (None, Some(max)) if max >= min => (max - min) / step + 1,
                _ => {
                    return Err(
                        "SLURM_ARRAY_TASK_ID is set but neither SLURM_ARRAY_TASK_COUNT nor \
                         SLURM_ARRAY_TASK_MAX: is this a job array (sbatch --array)?"
                            .into(),
                    );
                }
            };
            if id < min || (id - min) % step != 0 {
                return Err(format!(
                    "SLURM_ARRAY_TASK_ID={id} is not in the array from {min} by {step}"
                ));
            }
            return Self::new((id - min) / step + 1, count)
                .map_err(|e| format!("SLURM_ARRAY_TASK_ID={id} of {count} tasks from {min}: {e}"));
        }
        if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            let count = number(SHARD_COUNT_VARIABLE)?.ok_or_else(|| {
                format!(
                    "JOB_COMPLETION_INDEX is set but {SHARD_COUNT_VARIABLE} is not: set it to the \
                     indexed Job's completions"
                )
            })?;
            return Self::new(index + 1, count).map_err(|e| {
                format!("JOB_COMPLETION_INDEX={index} with {SHARD_COUNT_VARIABLE}={count}: {e}")
            });
        }
        Err(
            "--shard auto needs a scheduler's variables: SLURM_ARRAY_TASK_ID with \
             SLURM_ARRAY_TASK_COUNT (a SLURM job array), or JOB_COMPLETION_INDEX with \
             ELCON_SHARD_COUNT (a Kubernetes indexed Job); none is set"
                .into(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            pairs
                .iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn shards_partition_the_indices() {
        let total = 10;
        let mut seen = vec![0; total];
        for k in 1..=4 {
            let s = Shard::new(k, 4).unwrap();
            let n = s.len_of(total);
            for j in 0..n {
                let i = s.nth(j);
                assert!(s.contains(i) && i < total);
                seen[i] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
        assert_eq!(Shard::new(4, 4).unwrap().len_of(2), 0);
        assert!(Shard::new(0, 3).is_err() && Shard::new(4, 3).is_err());
        assert_eq!("2/8".parse::<Shard>().unwrap().to_string(), "2/8");
        assert!("4/3".parse::<Shard>().unwrap_err().contains("1 <= K <= N"));
    }

    #[test]
    fn slurm_arrays_give_k_and_n() {
        let s = Shard::from_scheduler(env(&[
            ("SLURM_ARRAY_TASK_ID", "0"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
        ]));
        assert_eq!(s, Ok(Shard { index: 1, count: 3 }));
        // --array=1-8: MIN and MAX without COUNT.
        let s = Shard::from_scheduler(env(&[
            ("SLURM_ARRAY_TASK_ID", "8"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "8"),
        ]));
        assert_eq!(s, Ok(Shard { index: 8, count: 8 }));
        // --array=0-10:5 is tasks 0, 5, 10.
        let s = Shard::from_scheduler(env(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_MAX", "10"),
            ("SLURM_ARRAY_TASK_STEP", "5"),
        ]));
        assert_eq!(s, Ok(Shard { index: 2, count: 3 }));
        let e = Shard::from_scheduler(env(&[("SLURM_ARRAY_TASK_ID", "2")])).unwrap_err();
        assert!(e.contains("SLURM_ARRAY_TASK_COUNT"), "{e}");
        let e = Shard::from_scheduler(env(&[
            ("SLURM_ARRAY_TASK_ID", "x"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]))
        .unwrap_err();
        assert!(e.contains("not a whole number"), "{e}");
    }

    #[test]
    fn indexed_jobs_need_the_count() {
        let s = Shard::from_scheduler(env(&[
            ("JOB_COMPLETION_INDEX", "2"),
            ("ELCON_SHARD_COUNT", "3"),
        ]));
        assert_eq!(s, Ok(Shard { index: 3, count: 3 }));
        let e = Shard::from_scheduler(env(&[("JOB_COMPLETION_INDEX", "2")])).unwrap_err();
        assert!(e.contains("ELCON_SHARD_COUNT"), "{e}");
        let e = Shard::from_scheduler(env(&[
            ("JOB_COMPLETION_INDEX", "3"),
            ("ELCON_SHARD_COUNT", "3"),
        ]))
        .unwrap_err();
        assert!(e.contains("1 <= K <= N"), "{e}");
        let e = Shard::from_scheduler(env(&[])).unwrap_err();
        assert!(e.contains("none is set"), "{e}");
    }
}
