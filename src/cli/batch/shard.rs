//! Which share of the models one batch process takes: shard K of N (0-based K) takes the
//! models at positions K, K + N, K + 2N, ... of the sorted list.

use anyhow::{bail, Context};

/// Shard `index` of `count` (0 ≤ index < count).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 0-based shard index.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole list.
    pub const ALL: Self = Self { index: 0, count: 1 };

    /// Parses `K/N` (0-based K).
    ///
    /// # Errors
    /// Not two numbers, N = 0, or K ≥ N.
    pub fn parse(text: &str) -> anyhow::Result<Self> {
        let (k, n) = text
            .split_once('/')
            .with_context(|| format!("--shard {text}: expected K/N, e.g. 0/4 (K is 0-based)"))?;
        let index = k
            .trim()
            .parse()
            .with_context(|| format!("--shard {text}: K is not a number"))?;
        let count = n
            .trim()
            .parse()
            .with_context(|| format!("--shard {text}: N is not a number"))?;
        Self::new(index, count).with_context(|| format!("--shard {text}"))
    }

    /// Shard `index` of `count`, checked.
    ///
    /// # Errors
    /// `count` = 0 or `index` ≥ `count`.
    pub fn new(index: usize, count: usize) -> anyhow::Result<Self> {
        if count == 0 {
            bail!("the number of shards must be at least 1");
        }
        if index >= count {
            bail!("shard index {index} is not below the number of shards {count} (indices are 0-based: 0 to {})", count - 1);
        }
        Ok(Self { index, count })
    }

    /// The shard from the command line and the environment, and where it came from:
    /// `--shard K/N`; else the index from `JOB_COMPLETION_INDEX` (Kubernetes Indexed Job; the
    /// count from `--shards N`) or from Slurm's `SLURM_ARRAY_TASK_ID` (minus
    /// `SLURM_ARRAY_TASK_MIN`, divided by `SLURM_ARRAY_TASK_STEP`; the count from `--shards N`
    /// or `SLURM_ARRAY_TASK_COUNT`); else the whole list.
    ///
    /// # Errors
    /// A malformed value, `--shards` without an index, or an index out of range.
    pub fn resolve(
        shard: Option<&str>,
        shards: Option<usize>,
        env: &dyn Fn(&str) -> Option<String>,
    ) -> anyhow::Result<(Self, String)> {
        if let Some(text) = shard {
            return Ok((Self::parse(text)?, "--shard".into()));
        }
        let number = |name: &str| -> anyhow::Result<Option<usize>> {
            env(name)
                .map(|v| {
                    v.trim()
                        .parse::<usize>()
                        .with_context(|| format!("{name}={v} is not a number"))
                })
                .transpose()
        };
        if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            let Some(count) = shards else {
                bail!("JOB_COMPLETION_INDEX={index} is set (a Kubernetes Indexed Job): give the number of shards with --shards N (the Job's completions)");
            };
            let shard = Self::new(index, count).context("JOB_COMPLETION_INDEX and --shards")?;
            return Ok((shard, "JOB_COMPLETION_INDEX".into()));
        }
        if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let step = number("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
            let Some(offset) = id.checked_sub(min) else {
                bail!("SLURM_ARRAY_TASK_ID={id} is below SLURM_ARRAY_TASK_MIN={min}");
            };
            let Some(count) = shards.or(number("SLURM_ARRAY_TASK_COUNT")?) else {
                bail!("SLURM_ARRAY_TASK_ID={id} is set but neither --shards N nor SLURM_ARRAY_TASK_COUNT");
            };
            let shard = Self::new(offset / step, count).context("SLURM_ARRAY_TASK_ID")?;
            return Ok((shard, "SLURM_ARRAY_TASK_ID".into()));
        }
        match shards {
            Some(1) | None => Ok((Self::ALL, "the whole list".into())),
            Some(n) => bail!("--shards {n} needs a shard index: --shard K/{n}, or JOB_COMPLETION_INDEX or SLURM_ARRAY_TASK_ID in the environment"),
        }
    }

    /// True when the model at `position` of the sorted list is this shard's.
    pub fn takes(self, position: usize) -> bool {
        position % self.count == self.index
    }

    /// `K/N`.
    pub fn label(self) -> String {
        format!("{}/{}", self.index, self.count)
    }

    /// The shard's log file name: `batch-KofN.jsonl`.
    pub fn log_name(self) -> String {
        format!("batch-{}of{}.jsonl", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            vars.iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn shards_from_flags_and_environment() {
        let none = env(&[]);
        assert_eq!(
            Shard::resolve(Some("2/3"), None, &none).unwrap().0,
            Shard { index: 2, count: 3 }
        );
        assert!(Shard::resolve(Some("3/3"), None, &none).is_err());
        assert_eq!(Shard::resolve(None, None, &none).unwrap().0, Shard::ALL);
        assert!(Shard::resolve(None, Some(4), &none).is_err());
        let k8s = env(&[("JOB_COMPLETION_INDEX", "1")]);
        assert_eq!(
            Shard::resolve(None, Some(4), &k8s).unwrap().0,
            Shard { index: 1, count: 4 }
        );
        assert!(Shard::resolve(None, None, &k8s).is_err());
        let slurm = env(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ]);
        assert_eq!(
            Shard::resolve(None, None, &slurm).unwrap().0,
            Shard { index: 4, count: 8 }
        );
        let shard = Shard { index: 1, count: 3 };
        let taken: Vec<usize> = (0..8).filter(|&i| shard.takes(i)).collect();
        assert_eq!(taken, vec![1, 4, 7]);
    }
}
