import {
  ActionIcon,
  Badge,
  Box,
  Button,
  Center,
  Chip,
  CloseButton,
  Group,
  Loader,
  ScrollArea,
  Select,
  Table,
  Text,
  TextInput,
  Tooltip,
} from "@mantine/core";
import { useLocalStorage } from "@mantine/hooks";
import { IconChevronDown, IconChevronRight, IconChevronUp, IconSearch, IconTrash } from "@tabler/icons-react";
import { Fragment, type PointerEvent as ReactPointerEvent, useEffect, useMemo, useRef, useState } from "react";
import type { EventLevel, EventOut } from "../../api/types";
import { fixed, levelColor } from "../../lib/format";
import { notifyError } from "../../lib/notify";
import { useStore } from "../../store/createStore";
import { clearEvents, eventFocusStore, eventsStore } from "../../store/events";

type SourceKind = EventOut["source_kind"];
const KINDS: { value: SourceKind; label: string; color: string }[] = [
  { value: "axis", label: "Axis", color: "blue" },
  { value: "group", label: "Group", color: "grape" },
  { value: "slave", label: "Slave", color: "teal" },
  { value: "instruction", label: "Instruction", color: "indigo" },
  { value: "controller", label: "Controller", color: "gray" },
];
const KIND_OF = Object.fromEntries(KINDS.map((k) => [k.value, k]));

/** Case-insensitive match of every word of `q` against what a row shows (and its cause/correction). */
function matches(e: EventOut, words: string[]): boolean {
  if (!words.length) return true;
  const hay = `${e.code} ${e.level} ${e.source} ${e.source_name} ${e.instruction} ${e.message} ${e.cause} ${e.correction} ${e.detail}`.toLowerCase();
  return words.every((w) => hay.includes(w));
}

const LEVELS: { value: EventLevel; label: string }[] = [
  { value: "major fault", label: "Major" },
  { value: "partial fault", label: "Partial" },
  { value: "minor fault", label: "Minor" },
  { value: "observation", label: "Observation" },
  { value: "information", label: "Information" },
];
const ALL_LEVELS = LEVELS.map((l) => l.value as string);
const MIN_H = 90;
const MAX_SHOWN = 500;

function EventRow({ e, open, focused, onToggle }: { e: EventOut; open: boolean; focused: boolean; onToggle: () => void }) {
  const hasMore = Boolean(e.cause || e.correction || e.detail);
  const kind = KIND_OF[e.source_kind] ?? KIND_OF.controller;
  return (
    <Fragment>
      <Table.Tr className="event-row" onClick={onToggle} data-testid={`event-${e.seq}`} data-level={e.level}
        data-source-kind={e.source_kind} data-focused={focused ? "true" : undefined}
        bg={focused ? "yellow.0" : undefined}>
        <Table.Td w={22} px={4}>
          {hasMore ? open ? <IconChevronDown size={12} /> : <IconChevronRight size={12} /> : null}
        </Table.Td>
        <Table.Td className="num">{fixed(e.time_s, 3)}</Table.Td>
        <Table.Td className="num">{e.cycle}</Table.Td>
        <Table.Td>
          <Badge size="xs" color={levelColor(e.level)} variant={e.level.endsWith("fault") ? "filled" : "light"}
            style={{ textTransform: "none" }}>
            {e.level}
          </Badge>
        </Table.Td>
        <Table.Td style={{ whiteSpace: "nowrap" }} title={e.source}>
          <Group gap={6} wrap="nowrap">
            <Badge size="xs" variant="outline" color={kind.color} w={74} style={{ textTransform: "none", flex: "none" }}
              data-testid="event-source-kind">
              {kind.label}
            </Badge>
            <Text size="xs" span>
              {e.source_name || e.source}
            </Text>
          </Group>
        </Table.Td>
        <Table.Td className="num" style={{ textAlign: "left" }}>
          {e.code}
        </Table.Td>
        <Table.Td title={hasMore ? [e.cause && `Cause: ${e.cause}`, e.correction && `Correction: ${e.correction}`].filter(Boolean).join("\n") : undefined}>
          {e.message}
          {e.instruction && e.instruction !== e.source_name && (
            <Text span size="xs" c="dimmed" ml={6}>
              · {e.instruction}
            </Text>
          )}
        </Table.Td>
      </Table.Tr>
      {open && hasMore && (
        <Table.Tr className="event-detail" data-testid={`event-detail-${e.seq}`}>
          <Table.Td />
          <Table.Td colSpan={6}>
            {e.cause && (
              <Text size="xs">
                <b>Cause:</b> {e.cause}
              </Text>
            )}
            {e.correction && (
              <Text size="xs">
                <b>Correction:</b> {e.correction}
              </Text>
            )}
            {e.detail && (
              <Text size="xs" c="dimmed">
                <b>Detail:</b> {e.detail}
              </Text>
            )}
          </Table.Td>
        </Table.Tr>
      )}
    </Fragment>
  );
}

/** The controller's event log: bottom panel, resizable by its top edge, collapsible. Newest events first. */
export function EventLog() {
  const { status, events } = useStore(eventsStore, (s) => s);
  const [height, setHeight] = useLocalStorage({ key: "mcstudio.eventlog.height", defaultValue: 170 });
  const [collapsed, setCollapsed] = useLocalStorage({ key: "mcstudio.eventlog.collapsed", defaultValue: false });
  const [levels, setLevels] = useState<string[]>(ALL_LEVELS);
  const [kind, setKind] = useState<string | null>(null);
  const [query, setQuery] = useState("");
  const [openSeq, setOpenSeq] = useState<number | null>(null);
  const [focusSeq, setFocusSeq] = useState<number | null>(null);
  const focus = useStore(eventFocusStore, (s) => s);
  const scrollTo = useRef<number | null>(null);

  // "Show in event log" from a notification: open the log, clear the filters, unfold and highlight the event
  useEffect(() => {
    if (!focus) return;
    setCollapsed(false);
    setLevels(ALL_LEVELS);
    setKind(null);
    setQuery("");
    setOpenSeq(focus.seq);
    setFocusSeq(focus.seq);
    scrollTo.current = focus.seq;
  }, [focus, setCollapsed]);
  useEffect(() => {
    if (scrollTo.current === null) return;
    const row = document.querySelector(`[data-testid="event-${scrollTo.current}"]`);
    if (row) {
      row.scrollIntoView({ block: "nearest" });
      scrollTo.current = null;
    }
  });
  const [dragging, setDragging] = useState(false);
  const drag = useRef<{ y: number; h: number } | null>(null);

  const shown = useMemo(() => {
    const words = query.toLowerCase().split(/\s+/).filter(Boolean);
    const out: EventOut[] = [];
    for (let i = events.length - 1; i >= 0 && out.length < MAX_SHOWN; i--) {
      const e = events[i];
      if (levels.includes(e.level) && (kind === null || e.source_kind === kind) && matches(e, words)) out.push(e);
    }
    return out;
  }, [events, levels, kind, query]);
  const filtered = levels.length !== ALL_LEVELS.length || kind !== null || query.trim() !== "";

  const faults = useMemo(() => events.filter((e) => e.level.endsWith("fault")).length, [events]);

  const onDown = (e: ReactPointerEvent<HTMLDivElement>) => {
    drag.current = { y: e.clientY, h: height };
    e.currentTarget.setPointerCapture(e.pointerId);
    setDragging(true);
  };
  const onMove = (e: ReactPointerEvent<HTMLDivElement>) => {
    if (!drag.current) return;
    const max = Math.max(MIN_H, window.innerHeight - 260);
    setHeight(Math.min(max, Math.max(MIN_H, drag.current.h + drag.current.y - e.clientY)));
  };
  const onUp = () => {
    drag.current = null;
    setDragging(false);
  };

  const clear = async () => {
    try {
      await clearEvents();
    } catch (err) {
      notifyError("Clear event log", err);
    }
  };

  return (
    <Box
      data-testid="event-log"
      style={{ flex: "none", display: "flex", flexDirection: "column", background: "white" }}
    >
      {!collapsed && (
        <div
          className="resize-handle"
          data-dragging={dragging ? "true" : "false"}
          onPointerDown={onDown}
          onPointerMove={onMove}
          onPointerUp={onUp}
          onPointerCancel={onUp}
          title="Drag to resize"
        />
      )}
      <Group
        gap="xs"
        px="xs"
        py={3}
        wrap="nowrap"
        style={{
          borderTop: collapsed ? "1px solid var(--mantine-color-gray-3)" : undefined,
          borderBottom: "1px solid var(--mantine-color-gray-3)",
          background: "var(--mantine-color-gray-0)",
        }}
      >
        <Tooltip label={collapsed ? "Show the event log" : "Hide the event log"}>
          <ActionIcon size="sm" onClick={() => setCollapsed(!collapsed)} aria-label="Toggle event log"
            data-testid="event-log-toggle">
            {collapsed ? <IconChevronUp size={14} /> : <IconChevronDown size={14} />}
          </ActionIcon>
        </Tooltip>
        <Text size="xs" fw={700} tt="uppercase" c="gray.7" style={{ letterSpacing: "0.03em" }}>
          Event log
        </Text>
        <Badge size="xs" variant="default" data-testid="event-count">
          {events.length}
        </Badge>
        {faults > 0 && (
          <Badge size="xs" color="orange" variant="light">
            {faults} fault{faults === 1 ? "" : "s"}
          </Badge>
        )}
        <Box style={{ flex: 1 }} />
        {!collapsed && (
          <TextInput size="xs" w={170} placeholder="Filter text, code…" value={query} data-testid="event-search"
            aria-label="Filter the event log by text" leftSection={<IconSearch size={12} />}
            onChange={(ev) => setQuery(ev.currentTarget.value)}
            rightSection={query ? <CloseButton size="xs" aria-label="Clear the text filter" onClick={() => setQuery("")} /> : null}
            styles={{ input: { height: 22, minHeight: 22 } }} />
        )}
        {!collapsed && (
          <Select size="xs" w={124} placeholder="All sources" value={kind} onChange={setKind} clearable
            data={KINDS.map((k) => ({ value: k.value, label: k.label }))} data-testid="event-source-filter"
            aria-label="Filter the event log by source kind" comboboxProps={{ withinPortal: true }}
            styles={{ input: { height: 22, minHeight: 22 } }} />
        )}
        {!collapsed && (
          <Chip.Group multiple value={levels} onChange={setLevels}>
            <Group gap={4} wrap="nowrap" data-testid="event-level-filter">
              {LEVELS.map((l) => (
                <Chip key={l.value} value={l.value} size="xs" color={levelColor(l.value).split(".")[0]} variant="light">
                  {l.label}
                </Chip>
              ))}
            </Group>
          </Chip.Group>
        )}
        <Button size="compact-xs" variant="default" leftSection={<IconTrash size={12} />} onClick={() => void clear()}
          data-testid="event-clear">
          Clear
        </Button>
      </Group>
      {!collapsed && (
        <ScrollArea h={height} type="auto" offsetScrollbars={false}>
          {status === "loading" ? (
            <Center h={height - 10}>
              <Loader size="xs" />
            </Center>
          ) : shown.length === 0 ? (
            <Center h={height - 10}>
              <Text size="xs" c="dimmed">
                {status === "error"
                  ? "Cannot load the event log: check that the studio server is running."
                  : events.length && filtered
                    ? "No event matches the filters: widen the levels, the source or the text filter."
                    : "No events yet. Errors, warnings and notes of the controller appear here as they happen."}
              </Text>
            </Center>
          ) : (
            <Table stickyHeader highlightOnHover verticalSpacing={2} data-testid="event-table">
              <Table.Thead>
                <Table.Tr>
                  <Table.Th w={22} px={4} />
                  <Table.Th className="num" w={90}>
                    Time [s]
                  </Table.Th>
                  <Table.Th className="num" w={80}>
                    Cycle
                  </Table.Th>
                  <Table.Th w={110}>Level</Table.Th>
                  <Table.Th w={240}>Source</Table.Th>
                  <Table.Th w={86}>Code</Table.Th>
                  <Table.Th>Message</Table.Th>
                </Table.Tr>
              </Table.Thead>
              <Table.Tbody>
                {shown.map((e) => (
                  <EventRow key={e.seq} e={e} open={openSeq === e.seq} focused={focusSeq === e.seq}
                    onToggle={() => setOpenSeq(openSeq === e.seq ? null : e.seq)} />
                ))}
              </Table.Tbody>
            </Table>
          )}
        </ScrollArea>
      )}
    </Box>
  );
}
