import { Alert, Badge, Button, Checkbox, FileButton, Group, Loader, NumberInput, Text, TextInput } from "@mantine/core";
import { IconArrowBackUp, IconDeviceFloppy, IconDownload, IconFileImport, IconTrash } from "@tabler/icons-react";
import { useEffect, useMemo, useState } from "react";
import { notifyError, notifyOk } from "../../lib/notify";
import {
  DEFAULT_SOURCE,
  camCsvUrl,
  camEditorStore,
  editDraft,
  importCamCsv,
  openCamEditor,
  revertCam,
  saveCam,
  scheduleGenerate,
  useCamDirty,
  useCamEditor,
  type CamDraft,
} from "../../store/cams";
import type { NumValue } from "../../store/forms";
import { CamNodeTable } from "./CamNodeTable";
import { CamPlots, type CamSeries } from "./CamPlots";
import { CamTestRun } from "./CamTestRun";
import { DeleteCamModal } from "./DeleteCamModal";
import "./cams.css";

function fmt(v: number | null | undefined): string {
  if (v === null || v === undefined || !Number.isFinite(v)) return "—";
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(3);
  return String(+v.toPrecision(5));
}

function PropField({ label, unit, value, onChange, testId, error, placeholder, w = 112 }: {
  label: string; unit: string; value: NumValue; onChange: (v: NumValue) => void; testId: string; error?: string;
  placeholder?: string; w?: number;
}) {
  return (
    <NumberInput size="xs" label={label} value={value} onChange={onChange} data-testid={testId} w={w}
      error={error} placeholder={placeholder} hideControls allowDecimal thousandSeparator={false} autoComplete="off"
      rightSection={<Text size="10px" c="dimmed" pr={6}>{unit}</Text>} rightSectionWidth={unit.length * 6 + 14}
      rightSectionPointerEvents="none"
      styles={{ label: { fontSize: 11, color: "var(--mantine-color-gray-7)" }, input: { textAlign: "right" } }} />
  );
}

const setProp = (name: string, p: Partial<CamDraft>) => editDraft(name, (d) => ({ ...d, ...p }));

/** The cam editor of one cam table: nodes and property, four linked plots, characteristics, continuity, CSV. */
export function CamEditor({ name }: { name: string }) {
  const e = useCamEditor(name);
  const dirty = useCamDirty(name);
  const [deleting, setDeleting] = useState(false);

  useEffect(() => {
    void openCamEditor(name);
  }, [name]);

  const series: CamSeries | null = useMemo(() => {
    if (e?.draft && e.result) return e.result;
    if (e?.points) return { phase: e.points.phase, distance: e.points.distance, velocity: null, acceleration: null,
      jerk: null };
    return null;
  }, [e?.draft, e?.result, e?.points]);

  if (!e || e.status === "loading") return <Loader size="sm" m="md" />;
  if (e.status === "error") return <Alert color="red" m="md" title={`Cannot open ${name}`}>{e.error}</Alert>;

  const d = e.draft;
  const table = e.result?.characteristics.table ?? null;
  const jumps = e.result?.continuity ?? [];
  const general = Object.entries(e.issues).filter(([k]) => !k.startsWith("nodes["));

  const save = async () => {
    try {
      await saveCam(name);
      notifyOk(`Cam table ${name} saved`, "Saved to the project and downloaded to the controller");
    } catch (err) {
      notifyError(`Save ${name}`, err);
    }
  };
  const importCsv = async (file: File | null) => {
    if (!file) return;
    try {
      const out = await importCamCsv(name, await file.text());
      notifyOk(`Imported ${file.name}`, `${out.point_count} points into ${name}`);
    } catch (err) {
      notifyError(`Import ${file.name}`, err);
    }
  };
  const toNodes = () => {
    camEditorStore.set((s) => ({
      ...s,
      [name]: {
        ...s[name],
        draft: {
          nodes: DEFAULT_SOURCE.nodes.map((n) => ({ Phase: n.Phase, Distance: n.Distance ?? 0, Curve: String(n.Curve),
            ConnectingVelEnable: false, ConnectingVel: 0, ConnectingAccEnable: false, ConnectingAcc: 0,
            PhasePitch: n.PhasePitch ?? 0.1 })),
          CycleTime: 1, InitVel: 0, InitAcc: 0, masterVelocity: "", periodic: true, description: e.info?.description ?? "",
        },
      },
    }));
    scheduleGenerate(name, 0);
  };

  return (
    <div className="cam-editor" data-testid={`cam-editor-${name}`}>
      <div className="cam-bar">
        <Text fw={700} size="sm" data-testid="cam-editor-name">{name}</Text>
        {dirty ? (
          <Badge size="sm" color="orange" variant="light" data-testid="cam-dirty">Unsaved changes</Badge>
        ) : (
          <Badge size="sm" color="gray" variant="light" data-testid="cam-saved">Saved</Badge>
        )}
        {d ? (
          <TextInput size="xs" placeholder="Description" value={d.description} style={{ flex: 1, minWidth: 120 }}
            onChange={(ev) => setProp(name, { description: ev.currentTarget.value })} data-testid="cam-description"
            aria-label="Description" />
        ) : <div style={{ flex: 1 }} />}
        {e.generating && <Loader size={14} />}
        <Button size="xs" leftSection={<IconDeviceFloppy size={14} />} onClick={save} disabled={!d || !dirty}
          loading={e.saving} data-testid="cam-save">Save</Button>
        <Button size="xs" variant="default" leftSection={<IconArrowBackUp size={14} />} disabled={!dirty}
          onClick={() => revertCam(name)} data-testid="cam-revert">Revert</Button>
        <FileButton onChange={importCsv} accept=".csv,text/csv,text/plain">
          {(props) => (
            <Button {...props} size="xs" variant="default" leftSection={<IconFileImport size={14} />}
              data-testid="cam-import">Import CSV</Button>
          )}
        </FileButton>
        <Button size="xs" variant="default" component="a" href={camCsvUrl(name)} download={`${name}.csv`}
          leftSection={<IconDownload size={14} />} data-testid="cam-export"
          title={dirty ? "Exports the saved table (save first to export the edits)" : "The cam data as CSV"}>
          Export CSV
        </Button>
        <Button size="xs" variant="subtle" color="red" leftSection={<IconTrash size={14} />}
          onClick={() => setDeleting(true)} data-testid="cam-delete">Delete</Button>
      </div>

      <div className="cam-body">
        {d ? (
          <div className="cam-props">
            <PropField label="Cycle time" unit="s" value={d.CycleTime} testId="cam-cycle-time"
              onChange={(v) => setProp(name, { CycleTime: v })} error={e.issues["property.CycleTime"]} />
            <PropField label="Initial velocity" unit="u/s" value={d.InitVel} testId="cam-init-vel"
              onChange={(v) => setProp(name, { InitVel: v })} error={e.issues["property.InitVel"]} />
            <PropField label="Initial acceleration" unit="u/s²" value={d.InitAcc} testId="cam-init-acc"
              onChange={(v) => setProp(name, { InitAcc: v })} error={e.issues["property.InitAcc"]} />
            <PropField label="Master velocity" unit="u/s" value={d.masterVelocity} testId="cam-master-vel" w={124}
              placeholder={table ? `auto ${fmt(table.phase_end / table.cycle_time)}` : "auto"}
              onChange={(v) => setProp(name, { masterVelocity: v })} error={e.issues["master_velocity"]} />
            <Checkbox size="xs" label="Periodic" checked={d.periodic} mt={18} data-testid="cam-periodic"
              onChange={(ev) => setProp(name, { periodic: ev.currentTarget.checked })}
              title="Check continuity across the wrap to the next cycle" />
            <div className="cam-summary" data-testid="cam-summary">
              {table ? (
                <>
                  <Text size="xs"><b data-testid="cam-point-count">{table.point_count}</b> points · end phase{" "}
                    {fmt(table.phase_end)} · distance {fmt(table.distance_min)} … {fmt(table.distance_max)}</Text>
                  <Text size="xs" ff="monospace" data-testid="cam-table-max">
                    v max {fmt(table.v_max)} · a max {fmt(table.a_max)} · j max {fmt(table.j_max)} at{" "}
                    {fmt(table.master_velocity)} u/s
                  </Text>
                  <Text size="xs" ff="monospace" c="dimmed" data-testid="cam-table-dim">
                    Vm {fmt(table.Vm)} · Am {fmt(table.Am)} · Jm {fmt(table.Jm)}
                  </Text>
                </>
              ) : <Text size="xs" c="dimmed">—</Text>}
            </div>
          </div>
        ) : (
          <Alert color="blue" variant="light" py={6} data-testid="cam-imported">
            <Group gap={8}>
              <Text size="xs">
                {e.info?.point_count} points imported as data (no nodes). The plot shows the displacement.
              </Text>
              <Button size="compact-xs" variant="light" onClick={toNodes} data-testid="cam-to-nodes">
                Replace with nodes
              </Button>
            </Group>
          </Alert>
        )}
        {general.length > 0 && (
          <Alert color="red" variant="light" py={4} data-testid="cam-issues">
            {general.map(([k, m]) => <Text size="xs" key={k}><b>{k}</b>: {m}</Text>)}
          </Alert>
        )}
        {jumps.length > 0 && (
          <Text size="xs" c="orange.8" data-testid="cam-continuity">
            {jumps.length} continuity warning{jumps.length > 1 ? "s" : ""}: {jumps.map((j) => j.message).join("; ")}
          </Text>
        )}
        <CamPlots data={series} units="u" testId="cam-plots" />
        {d && (
          <CamNodeTable name={name} nodes={d.nodes} issues={e.issues}
            segments={e.result?.characteristics.segments ?? null} jumps={jumps} />
        )}
        {e.info && (
          <CamTestRun name={name} phaseEnd={e.info.phase_end} dirty={dirty}
            defaultVelocity={table ? +(table.phase_end / table.cycle_time).toPrecision(6) : 360} />
        )}
      </div>
      <DeleteCamModal name={deleting ? name : null} onClose={() => setDeleting(false)} />
    </div>
  );
}
