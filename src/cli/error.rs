//! How a command failed, apart from the commands themselves: every command
//! returns it and the output writer (`write.rs`) builds it, so it sits below
//! both.

/// How a batch run failed, with the exit code it maps to.
#[derive(Debug)]
pub enum BatchError {
    /// Bad input: exit 2.
    Input(anyhow::Error),
    /// The run itself failed: exit 1.
    Run(anyhow::Error),
}

impl BatchError {
    /// `error`, as bad input (exit 2) if `input`, else as a failed run.
    pub fn of(error: anyhow::Error, input: bool) -> Self {
        if input { Self::Input(error) } else { Self::Run(error) }
    }
}
