//! family granular
