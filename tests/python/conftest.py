"""Shared by every test module: Ctrl-C behaves as in a terminal whatever started the tests.

A shell starting a job in the background without job control (a CI step run with `&`, nohup) ignores SIGINT, and
an ignored signal is inherited by every process started from there: the tests' own Ctrl-C (a SIGINT sent to
this process or to a command line they start) would then do nothing. Python's own handler is restored here, and
a process started by a test gets the default disposition back (a handler, unlike SIG_IGN, is not inherited)."""

import signal

if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
