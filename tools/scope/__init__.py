"""The PC side of the live data monitor (firmware/monitor, docs/monitor.md): the protocol
(monproto), the command (cli), and the core's state and fault names (mc_names)."""
