fn main() -> std::process::ExitCode {
    custom_closure::link();
    saltus::cli::main()
}
