//! Slices of a batch's sweep: `--shard K/N` runs the runs whose index i
//! (from 0) has `i mod N = K - 1`, so N processes, on one machine or many,
//! share a sweep without talking to each other and `elcon merge` joins
//! their tables. `--shard auto` takes K and N from the scheduler that
//! started the process: a SLURM job array (`SLURM_ARRAY_TASK_ID` with
//! `SLURM_ARRAY_TASK_COUNT`, or `SLURM_ARRAY_TASK_MIN`/`_MAX`, and
//! `SLURM_ARRAY_TASK_STEP`: task `id` of a regular range `--array=MIN-MAX:STEP`
//! is shard `(id - MIN) / STEP + 1` of `(MAX - MIN) / STEP + 1`; an array of
//! listed ids such as `--array=1,3,7` is refused), or a Kubernetes indexed Job
//! (`JOB_COMPLETION_INDEX`, from 0, with the count in `ELCON_SHARD_COUNT`,
//! the Job's `completions`); when both are set they must agree.
//! docs/scenes.md has a script for each.

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
pub(crate) const SHARD_COUNT_VARIABLE: &str = "ELCON_SHARD_COUNT";

/// The largest task id, count or step a scheduler's variable may hold:
/// SLURM's array task ids are 32-bit (and its arrays far smaller), and so
/// are a Kubernetes Job's completions. Below it, no id, count or step of
/// an array computed from them overflows.
const MAX_SCHEDULER_NUMBER: usize = u32::MAX as usize;

/// Why `--shard` or a scheduler's variables name no shard; each message
/// names the text or the variables at fault.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ShardError {
    /// `--shard` text that is not `K/N`.
    #[error("a shard is K/N, e.g. 2/8, or auto")]
    NotKOfN,
    /// K or N (the letter) of `--shard K/N` is not a whole number.
    #[error("{0} must be a whole number")]
    NotWhole(char),
    /// K outside `1..=N`.
    #[error("need 1 <= K <= N, got K = {index}, N = {count}")]
    OutOfRange {
        /// K.
        index: usize,
        /// N.
        count: usize,
    },
    /// What was given (the quoted `--shard` text, a scheduler's task), and
    /// why it names no shard.
    #[error("{given}: {reason}")]
    Given {
        /// The text or the task, as the message shows it.
        given: String,
        /// Why.
        reason: Box<ShardError>,
    },
    /// A scheduler's variable that is not a whole number.
    #[error("{name}={value}: not a whole number")]
    NotANumber {
        /// The variable.
        name: String,
        /// Its value.
        value: String,
    },
    /// A scheduler's variable beyond any task id or count (`u32::MAX`).
    #[error(
        "{name}={value}: more than {MAX_SCHEDULER_NUMBER}, beyond any job array's task id or \
         count (a scheduler's are 32-bit)"
    )]
    TooLarge {
        /// The variable.
        name: String,
        /// Its value.
        value: String,
    },
    /// SLURM and Kubernetes name different shards.
    #[error(
        "the SLURM job array says shard {slurm} (SLURM_ARRAY_TASK_ID) and the Kubernetes \
         indexed Job says shard {kubernetes} (JOB_COMPLETION_INDEX with {SHARD_COUNT_VARIABLE}): \
         unset the variables of the scheduler that did not start this process, or give \
         --shard K/N explicitly"
    )]
    Disagree {
        /// SLURM's.
        slurm: Shard,
        /// Kubernetes'.
        kubernetes: Shard,
    },
    /// `--shard auto` without a scheduler's variables.
    #[error(
        "--shard auto needs a scheduler's variables: SLURM_ARRAY_TASK_ID with \
         SLURM_ARRAY_TASK_COUNT (a SLURM job array), or JOB_COMPLETION_INDEX with \
         ELCON_SHARD_COUNT (a Kubernetes indexed Job); none is set"
    )]
    NoScheduler,
    /// A SLURM task id without the array's count or last id.
    #[error(
        "SLURM_ARRAY_TASK_ID is set but neither SLURM_ARRAY_TASK_COUNT nor \
         SLURM_ARRAY_TASK_MAX: is this a job array (sbatch --array)?"
    )]
    NotAnArray,
    /// A SLURM array whose first id is above its last.
    #[error(
        "SLURM_ARRAY_TASK_MIN={min} > SLURM_ARRAY_TASK_MAX={max}: not a job array's range \
         (its first task id is at most its last)"
    )]
    MinAboveMax {
        /// SLURM_ARRAY_TASK_MIN.
        min: usize,
        /// SLURM_ARRAY_TASK_MAX.
        max: usize,
    },
    /// A SLURM array's step of 0.
    #[error("SLURM_ARRAY_TASK_STEP=0: not a job array's step")]
    ZeroStep,
    /// A SLURM array that is not the regular range `MIN-MAX:STEP` (listed
    /// ids), so a task's id does not say which shard it is.
    #[error(
        "the SLURM job array is not a regular range: its {count} tasks \
         (SLURM_ARRAY_TASK_COUNT) are not the ids from {min} to {max} by {step} \
         (SLURM_ARRAY_TASK_MIN, _MAX, _STEP), which are {}, so a task's id does not say \
         which shard it is (an array of listed ids, e.g. --array=1,3,7?); submit a \
         range, --array=0-{} or --array=MIN-MAX:STEP, or give each task --shard K/N \
         explicitly",
        range_ids(.min, .max, .step),
        .count.saturating_sub(1)
    )]
    Irregular {
        /// SLURM_ARRAY_TASK_COUNT.
        count: usize,
        /// SLURM_ARRAY_TASK_MIN.
        min: usize,
        /// SLURM_ARRAY_TASK_MAX.
        max: usize,
        /// SLURM_ARRAY_TASK_STEP.
        step: usize,
    },
    /// A SLURM task id off its array's range.
    #[error("SLURM_ARRAY_TASK_ID={id} is not in the array from {min} to {max} by {step}")]
    NotInArray {
        /// SLURM_ARRAY_TASK_ID.
        id: usize,
        /// SLURM_ARRAY_TASK_MIN.
        min: usize,
        /// SLURM_ARRAY_TASK_MAX.
        max: usize,
        /// SLURM_ARRAY_TASK_STEP.
        step: usize,
    },
    /// A Kubernetes index without the Job's completions.
    #[error(
        "JOB_COMPLETION_INDEX is set but {SHARD_COUNT_VARIABLE} is not: set it to the \
         indexed Job's completions"
    )]
    NoCount,
}

impl ShardError {
    /// `reason`, about `given`.
    fn given(given: String, reason: ShardError) -> Self {
        Self::Given {
            given,
            reason: Box::new(reason),
        }
    }
}

/// How many ids the range from `min` to `max` by `step` holds ("none" when
/// `max < min`).
fn range_ids(&min: &usize, &max: &usize, &step: &usize) -> String {
    if max >= min {
        ((max - min) / step + 1).to_string()
    } else {
        "none".to_string()
    }
}

impl std::str::FromStr for Shard {
    type Err = ShardError;

    fn from_str(s: &str) -> Result<Self, ShardError> {
        let given = |reason| ShardError::given(format!("`{s}`"), reason);
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| given(ShardError::NotKOfN))?;
        let index: usize = k
            .trim()
            .parse()
            .map_err(|_| given(ShardError::NotWhole('K')))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| given(ShardError::NotWhole('N')))?;
        Self::new(index, count).map_err(given)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// A scheduler's variable read as a count: `None` when unset.
type Number<'a> = &'a dyn Fn(&str) -> Result<Option<usize>, ShardError>;

impl Shard {
    /// Shard K of N.
    ///
    /// # Errors
    /// `ShardError::OutOfRange` unless 1 <= K <= N.
    pub fn new(index: usize, count: usize) -> Result<Self, ShardError> {
        if count == 0 || index == 0 || index > count {
            return Err(ShardError::OutOfRange { index, count });
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
    /// table): a SLURM job array, or a Kubernetes indexed Job. When both
    /// are set they must name the same shard.
    ///
    /// # Errors
    /// A `ShardError` naming the variables when none is set, they are
    /// malformed, the SLURM array is not a regular range, or SLURM and
    /// Kubernetes give different shards.
    pub fn from_scheduler(var: impl Fn(&str) -> Option<String>) -> Result<Self, ShardError> {
        let number = |name: &str| -> Result<Option<usize>, ShardError> {
            let Some(value) = var(name) else {
                return Ok(None);
            };
            let (name, n) = (name.to_string(), value.trim().parse::<usize>());
            match n {
                Ok(n) if n <= MAX_SCHEDULER_NUMBER => Ok(Some(n)),
                Ok(_) => Err(ShardError::TooLarge { name, value }),
                Err(_) => Err(ShardError::NotANumber { name, value }),
            }
        };
        let slurm = Self::from_slurm(&number)?;
        let kubernetes = Self::from_indexed_job(&number)?;
        match (slurm, kubernetes) {
            (Some(slurm), Some(kubernetes)) if slurm != kubernetes => {
                Err(ShardError::Disagree { slurm, kubernetes })
            }
            (Some(s), _) | (None, Some(s)) => Ok(s),
            (None, None) => Err(ShardError::NoScheduler),
        }
    }

    /// The shard of a SLURM job array task, if `SLURM_ARRAY_TASK_ID` is
    /// set. The array must be a regular range (`--array=MIN-MAX[:STEP]`):
    /// task `id` is shard `(id - MIN) / STEP + 1` of `(MAX - MIN) / STEP + 1`.
    /// A list of ids (`--array=1,3,7`) has no such map, and is refused.
    fn from_slurm(number: Number<'_>) -> Result<Option<Self>, ShardError> {
        let Some(id) = number("SLURM_ARRAY_TASK_ID")? else {
            return Ok(None);
        };
        let count = number("SLURM_ARRAY_TASK_COUNT")?;
        let max = number("SLURM_ARRAY_TASK_MAX")?;
        let min = match (number("SLURM_ARRAY_TASK_MIN")?, count) {
            (Some(min), _) => min,
            // An old SLURM without MIN: a count alone means 0..count.
            (None, Some(_)) => 0,
            (None, None) => return Err(ShardError::NotAnArray),
        };
        if let Some(max) = max.filter(|&max| max < min) {
            return Err(ShardError::MinAboveMax { min, max });
        }
        let step = match number("SLURM_ARRAY_TASK_STEP")? {
            Some(0) => return Err(ShardError::ZeroStep),
            Some(s) => s,
            None => 1,
        };
        let (count, max) = match (count, max) {
            (Some(c), Some(max)) => (c, max),
            (Some(c), None) => (c, min + c.saturating_sub(1) * step),
            (None, Some(max)) if max >= min => ((max - min) / step + 1, max),
            (None, _) => return Err(ShardError::NotAnArray),
        };
        let regular = max >= min && (max - min) % step == 0 && (max - min) / step + 1 == count;
        if !regular {
            return Err(ShardError::Irregular {
                count,
                min,
                max,
                step,
            });
        }
        if id < min || id > max || (id - min) % step != 0 {
            return Err(ShardError::NotInArray { id, min, max, step });
        }
        let task = format!("SLURM_ARRAY_TASK_ID={id} of {count} tasks from {min}");
        Self::new((id - min) / step + 1, count)
            .map(Some)
            .map_err(|e| ShardError::given(task, e))
    }

    /// The shard of a Kubernetes indexed Job's pod, if
    /// `JOB_COMPLETION_INDEX` is set: index i (from 0) of
    /// `ELCON_SHARD_COUNT` completions is shard i + 1.
    fn from_indexed_job(number: Number<'_>) -> Result<Option<Self>, ShardError> {
        let Some(index) = number("JOB_COMPLETION_INDEX")? else {
            return Ok(None);
        };
        let count = number(SHARD_COUNT_VARIABLE)?.ok_or(ShardError::NoCount)?;
        let task = format!("JOB_COMPLETION_INDEX={index} with {SHARD_COUNT_VARIABLE}={count}");
        Self::new(index + 1, count)
            .map(Some)
            .map_err(|e| ShardError::given(task, e))
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

    /// The message of the scheduler's variables `pairs`, which name no shard.
    fn refused(pairs: &[(&str, &str)]) -> String {
        Shard::from_scheduler(env(pairs)).unwrap_err().to_string()
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
        assert!(
            "4/3"
                .parse::<Shard>()
                .unwrap_err()
                .to_string()
                .contains("1 <= K <= N")
        );
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
        let e = refused(&[("SLURM_ARRAY_TASK_ID", "2")]);
        assert!(e.contains("SLURM_ARRAY_TASK_COUNT"), "{e}");
        let e = refused(&[
            ("SLURM_ARRAY_TASK_ID", "x"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]);
        assert!(e.contains("not a whole number"), "{e}");
    }

    #[test]
    fn sparse_slurm_arrays_are_refused_with_what_to_do() {
        // --array=1,3,7: three tasks between 1 and 7, no uniform step.
        for step in [None, Some("1"), Some("2")] {
            let mut vars = vec![
                ("SLURM_ARRAY_TASK_ID", "3"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
                ("SLURM_ARRAY_TASK_MIN", "1"),
                ("SLURM_ARRAY_TASK_MAX", "7"),
            ];
            if let Some(s) = step {
                vars.push(("SLURM_ARRAY_TASK_STEP", s));
            }
            let e = Shard::from_scheduler(env(&vars)).unwrap_err().to_string();
            assert!(e.contains("not a regular range"), "{step:?}: {e}");
            assert!(
                e.contains("--shard K/N") && e.contains("--array=0-2"),
                "{e}"
            );
        }
        // --array=1-7:3 is tasks 1, 4, 7: task 7 is the third of three.
        let s = Shard::from_scheduler(env(&[
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "7"),
            ("SLURM_ARRAY_TASK_STEP", "3"),
        ]));
        assert_eq!(s, Ok(Shard { index: 3, count: 3 }));
        // An id off the range's step, and a zero step.
        let e = refused(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "7"),
            ("SLURM_ARRAY_TASK_STEP", "3"),
        ]);
        assert!(e.contains("not in the array from 1 to 7 by 3"), "{e}");
        let e = refused(&[
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "7"),
            ("SLURM_ARRAY_TASK_STEP", "0"),
        ]);
        assert!(e.contains("SLURM_ARRAY_TASK_STEP=0"), "{e}");
    }

    #[test]
    fn a_slurm_value_beyond_any_array_is_refused_naming_its_variable() {
        for var in [
            "SLURM_ARRAY_TASK_ID",
            "SLURM_ARRAY_TASK_COUNT",
            "SLURM_ARRAY_TASK_MIN",
            "SLURM_ARRAY_TASK_STEP",
        ] {
            let mut vars = vec![
                ("SLURM_ARRAY_TASK_ID", "1"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
                ("SLURM_ARRAY_TASK_MIN", "1"),
            ];
            vars.retain(|(n, _)| *n != var);
            vars.push((var, "18446744073709551615"));
            let e = Shard::from_scheduler(env(&vars)).unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("{var}=18446744073709551615: more than 4294967295")),
                "{e}"
            );
        }
        // The bound itself, in every variable at once: the last id,
        // MIN + (COUNT - 1) STEP, is computed without overflow.
        let bound = "4294967295";
        let s = Shard::from_scheduler(env(&[
            ("SLURM_ARRAY_TASK_ID", bound),
            ("SLURM_ARRAY_TASK_COUNT", bound),
            ("SLURM_ARRAY_TASK_MIN", bound),
            ("SLURM_ARRAY_TASK_STEP", bound),
        ]))
        .unwrap();
        assert_eq!(s, Shard::new(1, u32::MAX as usize).unwrap());
        let e = refused(&[
            ("JOB_COMPLETION_INDEX", "18446744073709551615"),
            (SHARD_COUNT_VARIABLE, "3"),
        ]);
        assert!(
            e.starts_with("JOB_COMPLETION_INDEX=18446744073709551615: more"),
            "{e}"
        );
    }

    #[test]
    fn a_slurm_array_whose_min_exceeds_its_max_is_said_so() {
        let e = refused(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "7"),
            ("SLURM_ARRAY_TASK_MAX", "3"),
        ]);
        assert!(
            e.starts_with("SLURM_ARRAY_TASK_MIN=7 > SLURM_ARRAY_TASK_MAX=3"),
            "{e}"
        );
        assert!(!e.contains("neither"), "{e}");
    }

    #[test]
    fn slurm_and_kubernetes_must_agree() {
        let both = |index: &str| {
            Shard::from_scheduler(env(&[
                ("SLURM_ARRAY_TASK_ID", "1"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
                ("SLURM_ARRAY_TASK_MIN", "0"),
                ("SLURM_ARRAY_TASK_MAX", "2"),
                ("JOB_COMPLETION_INDEX", index),
                ("ELCON_SHARD_COUNT", "3"),
            ]))
        };
        assert_eq!(both("1"), Ok(Shard { index: 2, count: 3 }));
        let e = both("2").unwrap_err().to_string();
        assert!(
            e.contains("SLURM") && e.contains("shard 2/3") && e.contains("Kubernetes"),
            "{e}"
        );
        assert!(
            e.contains("shard 3/3") && e.contains("JOB_COMPLETION_INDEX"),
            "{e}"
        );
    }

    #[test]
    fn indexed_jobs_need_the_count() {
        let s = Shard::from_scheduler(env(&[
            ("JOB_COMPLETION_INDEX", "2"),
            ("ELCON_SHARD_COUNT", "3"),
        ]));
        assert_eq!(s, Ok(Shard { index: 3, count: 3 }));
        let e = refused(&[("JOB_COMPLETION_INDEX", "2")]);
        assert!(e.contains("ELCON_SHARD_COUNT"), "{e}");
        let e = refused(&[("JOB_COMPLETION_INDEX", "3"), ("ELCON_SHARD_COUNT", "3")]);
        assert!(e.contains("1 <= K <= N"), "{e}");
        let e = refused(&[]);
        assert!(e.contains("none is set"), "{e}");
    }
}
