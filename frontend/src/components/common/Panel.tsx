import type { ReactNode } from "react";

interface PanelProps {
  title: ReactNode;
  /** Extra content at the right end of the title bar */
  right?: ReactNode;
  children: ReactNode;
  testId?: string;
  bodyPadding?: number;
}

/** A titled box of the test-run tab. */
export function Panel({ title, right, children, testId, bodyPadding }: PanelProps) {
  return (
    <section className="panel" data-testid={testId}>
      <div className="panel-title">
        <span style={{ flex: 1, minWidth: 0 }}>{title}</span>
        {right}
      </div>
      <div className="panel-body" style={bodyPadding !== undefined ? { padding: bodyPadding } : undefined}>
        {children}
      </div>
    </section>
  );
}
