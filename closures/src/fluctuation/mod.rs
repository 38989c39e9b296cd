//! family fluctuation
